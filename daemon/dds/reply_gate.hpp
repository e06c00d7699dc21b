#pragma once
// The server's half of "the client sees its answer": an answer is written only once the result
// writer has matched a reader of the participant that sent the request, or after a bounded wait.
// Discovery is not symmetric: a client may see the daemon's result writer (and send) before the
// daemon's writer has seen the client's result reader; a reliable write in that gap never reaches
// that reader, and transient-local replays only the last answer to it. rmw_cyclonedds does the
// same for ROS 2 services (rmw_send_response: the response writer's matched readers are checked
// for the requesting client's participant, up to 100 ms). The request carries no client identity,
// so the requester is the participant of the writer in the request's sample info.

#include <dds/dds.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <string>

namespace rangefit::daemon {

class ReplyGate {
 public:
  using Key = std::array<unsigned char, 16>;  // a participant GUID (DDSI: prefix + entity id)

  // request_reader: where requests arrive; result_writer: where their answers go.
  ReplyGate(dds_entity_t request_reader, dds_entity_t result_writer,
            std::chrono::milliseconds max_wait);

  // Remembers who sent request_id (the writer of the sample with this publication handle).
  void note(const std::string& request_id, dds_instance_handle_t publication_handle);
  // Waits until the requester of request_id (the oldest one noted and not yet answered) has a
  // result reader matched, at most max_wait; forgets it. No wait for ids never noted (HTTP,
  // TCP) and for participants that already timed out once without a matched reader since (a
  // sender that never reads, such as `ros2 topic pub`, costs one wait, not one per request).
  void wait_for_reader(const std::string& request_id);

  std::size_t pending() const;  // requesters noted and not yet answered (bounded)

 private:
  bool reader_matched(const Key& participant) const;

  dds_entity_t request_reader_;
  dds_entity_t result_writer_;
  std::chrono::milliseconds max_wait_;
  mutable std::mutex mutex_;  // note() runs on the main loop, wait_for_reader() on either thread
  std::map<std::string, std::deque<Key>> requesters_;  // by request id
  std::size_t count_ = 0;
  std::set<Key> readerless_;  // timed out, no matched reader seen since
};

}  // namespace rangefit::daemon
