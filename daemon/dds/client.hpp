#pragma once
// The DDS client side of rangefitd, shared by `rangefit request|watch` and the tests: sends a
// DetectRequest and waits for the Detection with the same request id; subscribes to clouds,
// diagnostics and state. Same topic table as the daemon (daemon/dds/topics.hpp).

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "daemon/dds/dds.hpp"
#include "daemon/dds/messages.hpp"
#include "daemon/dds/topics.hpp"

namespace rangefit::daemon {

class DdsClient {
 public:
  // ns, partition: the daemon's [ros] namespace and [dds] partition. Throws dds::DdsError.
  explicit DdsClient(std::uint32_t domain_id, const std::string& ns = "",
                     const std::string& partition = "");

  // Waits up to timeout for the daemon's request reader to match (discovery). False on timeout.
  bool wait_for_daemon(std::chrono::milliseconds timeout);
  // Publishes the request (sweep in internal units; linear_sweep: mm → m on the wire).
  bool send(const ScanRequest& request, bool linear_sweep);
  // Waits for the result of request_id; nullopt on timeout. Results of other ids are skipped.
  std::optional<DetectionResult> wait_result(const std::string& request_id,
                                             std::chrono::milliseconds timeout);

  // Polls every subscribed topic once for up to timeout; calls the non-null callbacks.
  struct Callbacks {
    std::function<void(const DetectionResult&)> detection{};
    std::function<void(const std::vector<DiagStatus>&)> diagnostics{};
    std::function<void(const PointCloud&)> cloud{};
    std::function<void(LifecycleState, const std::string& detail)> state{};
  };
  void poll(std::chrono::milliseconds timeout, const Callbacks& callbacks);

 private:
  dds::Participant participant_;
  topics::Writer<topics::Request> requests_;
  topics::Reader<topics::Detections> detections_;
  topics::Reader<topics::Diagnostics> diagnostics_;
  topics::Reader<topics::Cloud> clouds_;
  topics::Reader<topics::State> states_;
  std::vector<DetectionResult> pending_;
};

}  // namespace rangefit::daemon
