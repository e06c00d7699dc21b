#include "daemon/dds_service.hpp"

#include <cstdlib>

#include "daemon/models_msg.hpp"
#include "daemon/ros_frames.hpp"

namespace rangefit::daemon {

namespace topics {
dds::QosSpec cloud_qos(int depth) { return {true, false, depth}; }
dds::QosSpec latched_qos() { return {true, true, 1}; }
dds::QosSpec diagnostics_qos() { return {true, false, 10}; }
dds::QosSpec request_qos(int max_samples) { return {true, false, 1, true, max_samples}; }
// A keep-last writer replaces answers not yet acknowledged (a burst of "bad request" answers lost
// 5 of 300); keep-all keeps them until every matched reader has them. Late joiners get the last.
dds::QosSpec result_qos() { return {true, true, 1, true, 1024}; }
dds::QosSpec result_reader_qos() { return {true, true, 1, true, 4096}; }
dds::QosSpec tf_qos() { return {true, false, 100}; }
dds::QosSpec tf_static_qos() { return {true, true, 1}; }
}  // namespace topics

void apply_dds_config_uri(const std::string& uri) {
  if (!uri.empty()) setenv("CYCLONEDDS_URI", uri.c_str(), 1);
}

DdsService::DdsService(const DdsConfig& config)
    : participant_(config.domain_id),
      cloud_(participant_, topics::kCloud, &sensor_msgs_msg_dds__PointCloud2__desc,
             topics::cloud_qos(config.cloud_depth)),
      detections_(participant_, topics::kDetections, &rangefit_msgs_msg_dds__Detection__desc,
                  topics::result_qos()),
      pose_(participant_, topics::kPose, &geometry_msgs_msg_dds__PoseStamped__desc,
            topics::latched_qos()),
      state_(participant_, topics::kState, &rangefit_msgs_msg_dds__State__desc,
             topics::latched_qos()),
      diagnostics_(participant_, topics::kDiagnostics,
                   &diagnostic_msgs_msg_dds__DiagnosticArray__desc, topics::diagnostics_qos()),
      requests_(participant_, topics::kRequest, &rangefit_msgs_msg_dds__DetectRequest__desc,
                topics::request_qos(config.request_depth)),
      poses_(participant_, topics::kPoses, &geometry_msgs_msg_dds__PoseArray__desc,
             topics::latched_qos()),
      tf_(participant_, topics::kTf, &tf2_msgs_msg_dds__TFMessage__desc, topics::tf_qos()),
      tf_static_(participant_, topics::kTfStatic, &tf2_msgs_msg_dds__TFMessage__desc,
                 topics::tf_static_qos()),
      models_(participant_, topics::kModels, &rangefit_msgs_msg_dds__Models__desc,
              topics::latched_qos()),
      service_(participant_) {
  requests_.also_wake_on(service_.reader());
}

void DdsService::publish_frames(const DaemonConfig& config) {
  std::lock_guard lock(mutex_);
  frames_ = config.frames;
  const TfOut out(wall_time_now(), frames_.world, sensor_mounts(config));
  count(tf_static_.write(out.msg()));
  const ModelsOut models(config, frames_.world);
  count(models_.write(models.msg()));
}

void DdsService::on_cloud(const ScanRequest&, const PointCloud& cloud) {
  std::lock_guard lock(mutex_);
  const CloudOut out(cloud, frames_.world);  // fused clouds are in the world frame
  count(cloud_.write(out.msg()));
}

void DdsService::on_result(const DetectionResult& result) {
  std::lock_guard lock(mutex_);
  const DetectionOut out(result, frames_.world);
  count(detections_.write(out.msg()));
  if (result.found && !result.parts.empty()) {
    count(pose_.write(out.first_pose()));
    const PoseArrayOut poses(result, frames_.world);
    count(poses_.write(poses.msg()));
    const TfOut tf(result_stamp(result), frames_.world, part_frames(result));
    count(tf_.write(tf.msg()));
  }
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
  const int topic = requests_.take_each([&](const rangefit_msgs_msg_dds__DetectRequest_& msg) {
    std::string error;
    ScanRequest req = from_msg(msg, &error);
    handle(std::move(req), error);
  });
  return topic + service_.take(handle);
}

}  // namespace rangefit::daemon
