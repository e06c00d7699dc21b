#pragma once
// What the HTTP and TCP interfaces read back: the pipeline's sink in front of the DDS layer. It
// forwards every cloud, result and state change unchanged, and keeps the lifecycle state, the
// latest diagnostics and the last results by request id, so a client that asked over HTTP can
// wait for or poll the very result DDS subscribers get.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "daemon/dds/messages.hpp"
#include "daemon/service/pipeline.hpp"

namespace rangefit::daemon {

struct BoardState {
  LifecycleState state = LifecycleState::kStarting;
  std::string detail;
  std::string active_id;
  std::size_t queue_depth = 0;
  std::vector<DiagStatus> diagnostics;  // as last published on rt/diagnostics
};

class ResultBoard final : public ResultSink {
 public:
  // keep: finished results remembered (the oldest are forgotten; their spool entries stay).
  explicit ResultBoard(ResultSink& next, std::size_t keep = 64) : next_(next), keep_(keep) {}

  void on_cloud(const ScanRequest& request, const PointCloud& cloud) override;
  void on_result(const DetectionResult& result) override;
  void on_state(LifecycleState state, const std::string& detail, const std::string& active_id,
                std::size_t queue_depth) override;
  void set_diagnostics(std::vector<DiagStatus> statuses);

  // Marks id as queued before it is submitted, so a poll finds it running and a waiter does not
  // take an older result of the same id. False when a request of that id is still running.
  bool reserve(const std::string& id);
  // The result of id once it is there; nullopt after timeout or close().
  std::optional<DetectionResult> wait_for(const std::string& id, std::chrono::milliseconds timeout);

  enum class Lookup { kUnknown, kPending, kDone };
  Lookup find(const std::string& id, DetectionResult* out) const;
  std::vector<DetectionResult> latest(std::size_t n) const;  // newest first
  BoardState state() const;
  std::uint64_t generation() const;  // counts results; a page polls it cheaply
  void close();                      // the service stops: every waiter returns
  bool closed() const;

 private:
  ResultSink& next_;
  std::size_t keep_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::map<std::string, std::optional<DetectionResult>> by_id_;  // nullopt: queued or running
  std::deque<std::string> done_order_;                           // oldest first
  BoardState state_;
  std::uint64_t generation_ = 0;
  bool closed_ = false;
};

}  // namespace rangefit::daemon
