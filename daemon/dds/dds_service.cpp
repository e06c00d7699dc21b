#include "daemon/dds/dds_service.hpp"

#include <cstdlib>

#include "daemon/dds/dds_security.hpp"
#include "daemon/dds/models_msg.hpp"
#include "daemon/dds/ros_detections.hpp"
#include "daemon/dds/ros_frames.hpp"

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

// How long an answer waits for its requester's result reader to be matched. A client that
// started its reader just before sending is matched within milliseconds on one host; one that
// never reads costs this once (ReplyGate). rmw_cyclonedds waits 100 ms; a loaded cell's
// discovery (or a sanitizer build) can take longer.
constexpr auto kReplyReaderWait = std::chrono::milliseconds(500);

constexpr const char* kNodeName = "rangefitd";

}  // namespace

DdsService::DdsService(const DdsConfig& config)
    : participant_(config.domain_id, participant_config(config), config.partition),
      cloud_(participant_, topics::cloud(config.cloud_depth, config.ros_namespace)),
      detections_(participant_, topics::detections(config.ros_namespace)),
      pose_(participant_, topics::pose(config.ros_namespace)),
      state_(participant_, topics::state(config.ros_namespace)),
      diagnostics_(participant_, topics::diagnostics()),
      requests_(participant_, topics::request(config.request_depth, config.ros_namespace)),
      poses_(participant_, topics::poses(config.ros_namespace)),
      tf_(participant_, topics::tf()),
      tf_static_(participant_, topics::tf_static()),
      models_(participant_, topics::models(config.ros_namespace)),
      detections3d_(participant_, topics::detections3d(config.ros_namespace)),
      markers_(participant_, topics::markers(config.ros_namespace)),
      service_(participant_, config.ros_namespace),
      reply_gate_(requests_.get(), detections_.get(), kReplyReaderWait),
      discovery_(participant_, RosNode{kNodeName, ros_node_namespace(config.ros_namespace),
                                       {requests_.get(), service_.reader()},
                                       {cloud_.get(), detections_.get(), pose_.get(),
                                        state_.get(), diagnostics_.get(), poses_.get(),
                                        tf_.get(), tf_static_.get(), models_.get(),
                                        detections3d_.get(), markers_.get(),
                                        service_.writer()}},
                 config.ros_distro == "humble" ? RosGidLayout::kHumble
                                               : RosGidLayout::kIronOrLater),
      frame_prefix_(config.ros_namespace.empty() ? "" : config.ros_namespace + "/") {
  requests_.also_wake_on(service_.reader());
}

void DdsService::publish_frames(const DaemonConfig& config) {
  std::lock_guard lock(mutex_);
  frames_ = config.frames;
  frames_.world = frame_prefix_ + frames_.world;
  for (auto& [device, frame] : frames_.sensors) frame = frame_prefix_ + frame;
  auto mounts = sensor_mounts(config);
  for (auto& mount : mounts) mount.child_frame = frame_prefix_ + mount.child_frame;
  const TfOut out(wall_time_now(), frames_.world, std::move(mounts));
  count(tf_static_.write(out.msg()));
  const ModelsOut models(config, frames_.world);
  count(models_.write(models.msg()));
  shapes_.clear();
  for (const auto& object : config.objects) shapes_[object.name] = object.model;
}

void DdsService::on_cloud(const ScanRequest&, const PointCloud& cloud) {
  std::lock_guard lock(mutex_);
  const CloudOut out(cloud, frames_.world);  // fused clouds are in the world frame
  count(cloud_.write(out.msg()));
}

void DdsService::on_result(const DetectionResult& result) {
  reply_gate_.wait_for_reader(result.request_id);  // before the lock: clouds and state go on
  std::lock_guard lock(mutex_);
  const DetectionOut out(result, frames_.world);
  count(detections_.write(out.msg()));
  if (result.found && !result.parts.empty()) {
    count(pose_.write(out.first_pose()));
    const PoseArrayOut poses(result, frames_.world);
    count(poses_.write(poses.msg()));
    const TfOut tf(result_stamp(result), frames_.world, part_frames(result, frame_prefix_));
    count(tf_.write(tf.msg()));
  }
  // Every result, found or not: an empty array tells vision and rviz2 users nothing is there.
  const Detection3DArrayOut detections3d(result, frames_.world, shapes_, frame_prefix_);
  count(detections3d_.write(detections3d.msg()));
  const MarkerArrayOut markers(result, frames_.world, shapes_);
  count(markers_.write(markers.msg()));
  service_.answer(result, frames_.world);
}

void DdsService::on_state(LifecycleState state, const std::string& detail,
                          const std::string& active_id, std::size_t queue_depth) {
  std::lock_guard lock(mutex_);
  const StateOut out(state, detail, active_id, static_cast<std::uint32_t>(queue_depth),
                     frames_.world);
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
  const int topic = requests_.take_each_with_info(
      [&](const rangefit_msgs_msg_dds__DetectRequest_& msg, const dds_sample_info_t& info) {
        std::string error;
        ScanRequest req = from_msg(msg, &error);
        reply_gate_.note(req.id, info.publication_handle);  // handle() may answer at once
        handle(std::move(req), error);
      });
  return topic + service_.take(handle);
}

}  // namespace rangefit::daemon
