#include "daemon/dds/topics.hpp"

namespace rangefit::daemon::topics {

dds::QosSpec cloud_qos(int depth) { return {true, false, depth}; }
dds::QosSpec latched_qos(int depth) { return {true, true, depth}; }
dds::QosSpec diagnostics_qos() { return {true, false, 10}; }
dds::QosSpec request_qos(int depth) { return {true, false, depth}; }

Cloud cloud(int depth) {
  return {kCloud, &sensor_msgs_msg_dds__PointCloud2__desc, cloud_qos(depth)};
}
Detections detections(int depth) {
  return {kDetections, &rangefit_msgs_msg_dds__Detection__desc, latched_qos(depth)};
}
Pose pose() { return {kPose, &geometry_msgs_msg_dds__PoseStamped__desc, latched_qos()}; }
State state() { return {kState, &rangefit_msgs_msg_dds__State__desc, latched_qos()}; }
Diagnostics diagnostics() {
  return {kDiagnostics, &diagnostic_msgs_msg_dds__DiagnosticArray__desc, diagnostics_qos()};
}
Request request(int depth) {
  return {kRequest, &rangefit_msgs_msg_dds__DetectRequest__desc, request_qos(depth)};
}

}  // namespace rangefit::daemon::topics
