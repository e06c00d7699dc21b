#include "daemon/dds/client.hpp"

#include <thread>

#include "daemon/dds/cloud_msg_guard.hpp"

namespace rangefit::daemon {

DdsClient::DdsClient(std::uint32_t domain_id, const std::string& ns, const std::string& partition)
    : participant_(domain_id, {}, partition),
      requests_(participant_, topics::request(1024, ns)),
      detections_(participant_, topics::detections_reader(ns)),
      diagnostics_(participant_, topics::diagnostics()),
      clouds_(participant_, topics::cloud(2, ns)),
      states_(participant_, topics::state(ns)) {}

bool DdsClient::wait_for_daemon(std::chrono::milliseconds timeout) {
  // Both directions: the daemon's request reader (or the request would go nowhere) and its
  // result writer (or the answer would), polled with a backoff so that many clients starting at
  // once do not spin while discovery catches up.
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  auto pause = std::chrono::milliseconds(5);
  while (requests_.matched() == 0 || detections_.matched() == 0) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) return false;
    std::this_thread::sleep_for(std::min<std::chrono::nanoseconds>(pause, deadline - now));
    pause = std::min(pause * 2, std::chrono::milliseconds(200));
  }
  return true;
}

bool DdsClient::send(const ScanRequest& request, bool linear_sweep) {
  const RequestOut out(request, linear_sweep);
  return requests_.write(out.msg());
}

std::optional<DetectionResult> DdsClient::wait_result(const std::string& request_id,
                                                      std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    for (auto it = pending_.begin(); it != pending_.end(); ++it) {
      if (it->request_id == request_id) {
        DetectionResult r = std::move(*it);
        pending_.erase(it);
        return r;
      }
    }
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) return std::nullopt;
    if (detections_.wait(
            std::min<std::chrono::nanoseconds>(deadline - now, std::chrono::milliseconds(200)))) {
      detections_.take_each(
          [&](const rangefit_msgs_msg_dds__Detection_& m) { pending_.push_back(from_msg(m)); });
    }
  }
}

void DdsClient::poll(std::chrono::milliseconds timeout, const Callbacks& cb) {
  detections_.wait(timeout);
  detections_.take_each([&](const rangefit_msgs_msg_dds__Detection_& m) {
    if (cb.detection) cb.detection(from_msg(m));
  });
  diagnostics_.take_each([&](const diagnostic_msgs_msg_dds__DiagnosticArray_& m) {
    if (cb.diagnostics) cb.diagnostics(from_msg(m));
  });
  clouds_.take_each([&](const sensor_msgs_msg_dds__PointCloud2_& m) {
    if (cb.cloud) cb.cloud(cloud_from_wire(m));
  });
  states_.take_each([&](const rangefit_msgs_msg_dds__State_& m) {
    if (cb.state) {
      cb.state(static_cast<LifecycleState>(m.state), m.detail == nullptr ? "" : m.detail);
    }
  });
}

}  // namespace rangefit::daemon
