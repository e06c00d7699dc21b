#include "daemon/dds_service.hpp"

#include <cstdlib>

namespace rangefit::daemon {

namespace topics {
dds::QosSpec cloud_qos(int depth) { return {true, false, depth}; }
dds::QosSpec latched_qos() { return {true, true, 1}; }
dds::QosSpec diagnostics_qos() { return {true, false, 10}; }
dds::QosSpec request_qos(int depth) { return {true, false, depth}; }
}  // namespace topics

void apply_dds_config_uri(const std::string& uri) {
  if (!uri.empty()) setenv("CYCLONEDDS_URI", uri.c_str(), 1);
}

DdsService::DdsService(const DdsConfig& config)
    : participant_(config.domain_id),
      cloud_(participant_, topics::kCloud, &sensor_msgs_msg_dds__PointCloud2__desc,
             topics::cloud_qos(config.cloud_depth)),
      detections_(participant_, topics::kDetections, &rangefit_msgs_msg_dds__Detection__desc,
                  topics::latched_qos()),
      pose_(participant_, topics::kPose, &geometry_msgs_msg_dds__PoseStamped__desc,
            topics::latched_qos()),
      state_(participant_, topics::kState, &rangefit_msgs_msg_dds__State__desc,
             topics::latched_qos()),
      diagnostics_(participant_, topics::kDiagnostics,
                   &diagnostic_msgs_msg_dds__DiagnosticArray__desc, topics::diagnostics_qos()),
      requests_(participant_, topics::kRequest, &rangefit_msgs_msg_dds__DetectRequest__desc,
                topics::request_qos(config.request_depth)) {}

void DdsService::on_cloud(const ScanRequest&, const PointCloud& cloud) {
  const CloudOut out(cloud);
  std::lock_guard lock(mutex_);
  count(cloud_.write(out.msg()));
}

void DdsService::on_result(const DetectionResult& result) {
  const DetectionOut out(result);
  std::lock_guard lock(mutex_);
  count(detections_.write(out.msg()));
  if (result.found && !result.parts.empty()) count(pose_.write(out.first_pose()));
}

void DdsService::on_state(LifecycleState state, const std::string& detail,
                          const std::string& active_id, std::size_t queue_depth) {
  const StateOut out(state, detail, active_id, static_cast<std::uint32_t>(queue_depth));
  std::lock_guard lock(mutex_);
  count(state_.write(out.msg()));
}

void DdsService::publish_diagnostics(std::vector<DiagStatus> statuses) {
  const DiagnosticsOut out(std::move(statuses));
  std::lock_guard lock(mutex_);
  count(diagnostics_.write(out.msg()));
}

int DdsService::poll_requests(std::chrono::nanoseconds timeout,
                              const std::function<void(ScanRequest, const std::string&)>& handle) {
  if (!requests_.wait(timeout)) return 0;
  return requests_.take_each([&](const rangefit_msgs_msg_dds__DetectRequest_& msg) {
    std::string error;
    ScanRequest req = from_msg(msg, &error);
    handle(std::move(req), error);
  });
}

}  // namespace rangefit::daemon
