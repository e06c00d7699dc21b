#include "daemon/dds/dds_service.hpp"

#include <cstdlib>

#include "daemon/dds/dds_security.hpp"

namespace rangefit::daemon {

namespace {

// Cyclone's configuration for the daemon's participant: the configured URI (else what the process
// was started with), plus the [dds.security] fragment when security is on.
std::string participant_config(const DdsConfig& config) {
  std::string uri = config.config_uri;
  if (uri.empty() && config.security.enabled()) {
    const char* env = std::getenv("CYCLONEDDS_URI");
    uri = env != nullptr ? env : "";
  }
  return with_dds_security(uri, config.security);
}

}  // namespace

DdsService::DdsService(const DdsConfig& config)
    : participant_(config.domain_id, participant_config(config)),
      cloud_(participant_, topics::cloud(config.cloud_depth)),
      detections_(participant_, topics::detections()),
      pose_(participant_, topics::pose()),
      state_(participant_, topics::state()),
      diagnostics_(participant_, topics::diagnostics()),
      requests_(participant_, topics::request(config.request_depth)) {}

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
