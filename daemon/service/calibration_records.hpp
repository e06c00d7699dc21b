#pragma once
// What a calibration taken over several requests keeps between them: each request's recorded
// sweep or pose, by request id, so a later request can name earlier ones (`scans`). The newest
// kMaxCalibrationScans + 1 of a kind are kept, in memory: a restart forgets them; their files
// stay in the spool for the offline `rangefit calibrate`.

#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "daemon/service/request_validation.hpp"

namespace rangefit::daemon {

template <typename Record>
class CalibrationRecords {
 public:
  // Records under id, replacing an earlier record of that id; forgets the oldest beyond the cap.
  void record(const std::string& id, Record r) {
    for (auto it = records_.begin(); it != records_.end(); ++it) {
      if (it->first == id) {
        records_.erase(it);
        break;
      }
    }
    records_.emplace_back(id, std::move(r));
    while (records_.size() > kMaxCalibrationScans + 1) records_.pop_front();
  }
  const Record* find(const std::string& id) const {
    for (const auto& [name, r] : records_) {
      if (name == id) return &r;
    }
    return nullptr;
  }
  // Records `own` under id and returns the records `earlier` names, in order, followed by own.
  // When one of them is not held, returns nothing and names it in *unknown; own is recorded
  // either way, so a retry can name it.
  std::vector<Record> join(const std::string& id, Record own,
                           const std::vector<std::string>& earlier, std::string* unknown) {
    std::vector<Record> out;
    unknown->clear();
    for (const std::string& name : earlier) {
      const Record* r = find(name);
      if (r == nullptr) {
        *unknown = name;
        out.clear();
        break;
      }
      out.push_back(*r);
    }
    if (unknown->empty()) out.push_back(own);
    record(id, std::move(own));
    return out;
  }

 private:
  std::deque<std::pair<std::string, Record>> records_;
};

// The reason of a calibration request that names a record this service does not hold.
inline std::string unknown_record_reason(const std::string& target, const std::string& id,
                                         const std::string& file) {
  return "no " + target + " calibration scan \"" + id + "\" is known to this service (it keeps " +
         "the last " + std::to_string(kMaxCalibrationScans + 1) + " until it restarts; the " +
         "spool keeps each one's " + file + " for `rangefit calibrate " + target + "`)";
}

}  // namespace rangefit::daemon
