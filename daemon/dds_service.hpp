#pragma once
// rangefitd's DDS face: the writers and the request reader of issue 9's topic list, with their
// QoS, all ROS 2-compatible (rt/ prefix, <pkg>::msg::dds_::<Name>_ types, XCDR1):
//   rt/rangefit/cloud           sensor_msgs/PointCloud2     reliable, volatile, keep last 2
//   rt/rangefit/detections      rangefit_msgs/Detection     reliable, transient-local, depth 1
//   rt/rangefit/pose            geometry_msgs/PoseStamped   reliable, transient-local, depth 1
//   rt/rangefit/state           rangefit_msgs/State         reliable, transient-local, depth 1
//   rt/diagnostics              diagnostic_msgs/DiagnosticArray  reliable, volatile, depth 10
//   rt/rangefit/detect_request  rangefit_msgs/DetectRequest (read)  reliable, volatile
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

namespace rangefit::daemon {

namespace topics {
inline constexpr const char* kCloud = "rt/rangefit/cloud";
inline constexpr const char* kDetections = "rt/rangefit/detections";
inline constexpr const char* kPose = "rt/rangefit/pose";
inline constexpr const char* kState = "rt/rangefit/state";
inline constexpr const char* kDiagnostics = "rt/diagnostics";
inline constexpr const char* kRequest = "rt/rangefit/detect_request";
dds::QosSpec cloud_qos(int depth = 2);
dds::QosSpec latched_qos();  // detections, pose, state
dds::QosSpec diagnostics_qos();
dds::QosSpec request_qos(int depth = 16);
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

  // Waits up to timeout for requests and calls handle(request, error) for each one taken; error
  // is non-empty when the message is malformed. Returns the number handled.
  int poll_requests(std::chrono::nanoseconds timeout,
                    const std::function<void(ScanRequest, const std::string&)>& handle);

  std::uint64_t write_failures() const { return write_failures_; }

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
  std::uint64_t write_failures_ = 0;
};

}  // namespace rangefit::daemon
