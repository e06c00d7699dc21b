#pragma once
// rangefitd's DDS face: the writers and the request reader of issue 9's topic list, with their
// QoS, all ROS 2-compatible (rt/ prefix, <pkg>::msg::dds_::<Name>_ types, XCDR1):
//   rt/rangefit/cloud           sensor_msgs/PointCloud2     reliable, volatile, keep last 2
//   rt/rangefit/detections      rangefit_msgs/Detection     reliable, transient-local (last 1),
//                               keep-all (1024): every answer reaches every matched reader
//   rt/rangefit/pose            geometry_msgs/PoseStamped   reliable, transient-local, depth 1
//   rt/rangefit/state           rangefit_msgs/State         reliable, transient-local, depth 1
//   rt/diagnostics              diagnostic_msgs/DiagnosticArray  reliable, volatile, depth 10
//   rt/rangefit/poses           geometry_msgs/PoseArray     every part; reliable, transient-local
//   rt/rangefit/models          rangefit_msgs/Models        reliable, transient-local, depth 1
//   rt/tf                       tf2_msgs/TFMessage          every part as a frame; reliable, depth
//   100 rt/tf_static                tf2_msgs/TFMessage          the sensors' mounts;
//   transient-local rq/rangefit/detectRequest, rr/rangefit/detectReply: the ROS 2 service
//   (ros_service.hpp) rt/rangefit/detect_request  rangefit_msgs/DetectRequest (read)  reliable,
//   volatile, keep-all
//                               (dds.request_depth unread requests; beyond, the sender resends)
// The same QoS table is used by the clients (daemon/cli) so both sides always match.

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "daemon/config.hpp"
#include "daemon/dds.hpp"
#include "daemon/pipeline.hpp"
#include "daemon/ros_service.hpp"
#include "tf2_msgs.h"

namespace rangefit::daemon {

namespace topics {
inline constexpr const char* kCloud = "rt/rangefit/cloud";
inline constexpr const char* kDetections = "rt/rangefit/detections";
inline constexpr const char* kPose = "rt/rangefit/pose";
inline constexpr const char* kState = "rt/rangefit/state";
inline constexpr const char* kDiagnostics = "rt/diagnostics";
inline constexpr const char* kRequest = "rt/rangefit/detect_request";
inline constexpr const char* kPoses = "rt/rangefit/poses";
inline constexpr const char* kModels = "rt/rangefit/models";
inline constexpr const char* kTf = "rt/tf";
inline constexpr const char* kTfStatic = "rt/tf_static";
dds::QosSpec tf_qos();         // tf2's dynamic broadcaster: reliable, volatile, depth 100
dds::QosSpec tf_static_qos();  // tf2's static broadcaster: reliable, transient-local, depth 1
dds::QosSpec cloud_qos(int depth = 2);
dds::QosSpec latched_qos();  // detections, pose, state
dds::QosSpec diagnostics_qos();
dds::QosSpec request_qos(int max_samples = 64);
dds::QosSpec result_qos();         // rt/rangefit/detections, the daemon's writer
dds::QosSpec result_reader_qos();  // rt/rangefit/detections, the clients' reader
}  // namespace topics

// Points the Cyclone DDS configuration at uri (CYCLONEDDS_URI) unless empty. Must run before
// the first participant of the process is created.
void apply_dds_config_uri(const std::string& uri);

class DdsService final : public ResultSink {
 public:
  // Throws dds::DdsError when the domain or an entity cannot be created (start-up only).
  explicit DdsService(const DdsConfig& config);

  void on_cloud(const ScanRequest& request, const PointCloud& cloud) override;
  void on_result(const DetectionResult& result) override;
  void on_state(LifecycleState state, const std::string& detail, const std::string& active_id,
                std::size_t queue_depth) override;
  void publish_diagnostics(std::vector<DiagStatus> statuses);
  // The frames of `config` ([frames]) for every header from now on, its sensors' mounts on
  // rt/tf_static and its object models on rt/rangefit/models. At start-up and after each reload.
  void publish_frames(const DaemonConfig& config);

  // Waits up to timeout for requests and calls handle(request, error) for each one taken; error
  // is non-empty when the message is malformed. Returns the number handled.
  int poll_requests(std::chrono::nanoseconds timeout,
                    const std::function<void(ScanRequest, const std::string&)>& handle);

  std::uint64_t write_failures() const { return write_failures_ + service_.write_failures(); }

 private:
  void count(bool ok) { write_failures_ += ok ? 0 : 1; }

  dds::Participant participant_;
  std::mutex mutex_;  // writers are used from the pipeline worker and the main loop
  dds::Writer<sensor_msgs_msg_dds__PointCloud2_> cloud_;
  dds::Writer<rangefit_msgs_msg_dds__Detection_> detections_;
  dds::Writer<geometry_msgs_msg_dds__PoseStamped_> pose_;
  dds::Writer<rangefit_msgs_msg_dds__State_> state_;
  dds::Writer<diagnostic_msgs_msg_dds__DiagnosticArray_> diagnostics_;
  dds::Reader<rangefit_msgs_msg_dds__DetectRequest_> requests_;
  dds::Writer<geometry_msgs_msg_dds__PoseArray_> poses_;
  dds::Writer<tf2_msgs_msg_dds__TFMessage_> tf_;
  dds::Writer<tf2_msgs_msg_dds__TFMessage_> tf_static_;
  dds::Writer<rangefit_msgs_msg_dds__Models_> models_;
  RosDetectService service_;
  FramesConfig frames_;  // guarded by mutex_
  std::uint64_t write_failures_ = 0;
};

}  // namespace rangefit::daemon
