#pragma once
// What a calibration taken over several requests keeps between them: each request's recorded
// sweep or pose, by request id, so a later request can name earlier ones (`scans`). The newest
// kMaxCalibrationScans + 1 of a kind are kept, in memory: a restart forgets them; their files
// stay in the spool for the offline `rangefit calibrate`.

#include <deque>
#include <string>
#include <utility>

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
