#include "daemon/dds/reply_gate.hpp"

#include <algorithm>
#include <cstring>
#include <thread>
#include <vector>

namespace rangefit::daemon {
namespace {

// Requesters remembered at most: every DDS request is answered, so this only bounds a flood.
constexpr std::size_t kMaxPending = 4096;
constexpr std::size_t kMaxReaderless = 1024;
// How often the writer's matches are looked at while waiting (rmw_cyclonedds: 10 ms).
constexpr auto kPollPeriod = std::chrono::milliseconds(2);

ReplyGate::Key key_of(const dds_guid_t& guid) {
  ReplyGate::Key k{};
  static_assert(sizeof guid.v == std::tuple_size_v<ReplyGate::Key>);
  std::memcpy(k.data(), guid.v, k.size());
  return k;
}

}  // namespace

ReplyGate::ReplyGate(dds_entity_t request_reader, dds_entity_t result_writer,
                     std::chrono::milliseconds max_wait)
    : request_reader_(request_reader), result_writer_(result_writer), max_wait_(max_wait) {}

void ReplyGate::note(const std::string& request_id, dds_instance_handle_t publication_handle) {
  dds_builtintopic_endpoint_t* writer =
      dds_get_matched_publication_data(request_reader_, publication_handle);
  if (writer == nullptr) return;  // the writer is already gone: nobody to wait for
  const Key participant = key_of(writer->participant_key);
  dds_builtintopic_free_endpoint(writer);
  std::lock_guard lock(mutex_);
  if (count_ >= kMaxPending) return;
  requesters_[request_id].push_back(participant);
  ++count_;
}

void ReplyGate::wait_for_reader(const std::string& request_id) {
  Key participant;
  bool gave_up_before = false;
  {
    std::lock_guard lock(mutex_);
    const auto it = requesters_.find(request_id);
    if (it == requesters_.end()) return;
    participant = it->second.front();
    it->second.pop_front();
    if (it->second.empty()) requesters_.erase(it);
    --count_;
    gave_up_before = readerless_.contains(participant);
  }
  const auto deadline = std::chrono::steady_clock::now() + max_wait_;
  for (;;) {
    if (reader_matched(participant)) {
      if (gave_up_before) {
        std::lock_guard lock(mutex_);
        readerless_.erase(participant);
      }
      return;
    }
    if (gave_up_before || std::chrono::steady_clock::now() >= deadline) break;
    std::this_thread::sleep_for(kPollPeriod);
  }
  std::lock_guard lock(mutex_);
  if (readerless_.size() >= kMaxReaderless) readerless_.clear();
  readerless_.insert(participant);
}

std::size_t ReplyGate::pending() const {
  std::lock_guard lock(mutex_);
  return count_;
}

bool ReplyGate::reader_matched(const Key& participant) const {
  std::vector<dds_instance_handle_t> readers(64);
  for (;;) {
    const dds_return_t n =
        dds_get_matched_subscriptions(result_writer_, readers.data(), readers.size());
    if (n < 0) return false;
    if (static_cast<std::size_t>(n) <= readers.size()) {
      readers.resize(static_cast<std::size_t>(n));
      break;
    }
    readers.resize(static_cast<std::size_t>(n));  // more matched than room: ask again
  }
  return std::any_of(readers.begin(), readers.end(), [&](dds_instance_handle_t h) {
    dds_builtintopic_endpoint_t* reader = dds_get_matched_subscription_data(result_writer_, h);
    if (reader == nullptr) return false;
    const bool same = key_of(reader->participant_key) == participant;
    dds_builtintopic_free_endpoint(reader);
    return same;
  });
}

}  // namespace rangefit::daemon
