#include "daemon/dds/topics.hpp"

namespace rangefit::daemon::topics {

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

std::string in_namespace(const char* name, const std::string& ns) {
  const std::string n(name);
  if (ns.empty() || n.size() < 3 || n[2] != '/') return n;
  return n.substr(0, 3) + ns + "/" + n.substr(3);  // after the rt/ (rq/, rr/) prefix
}

Cloud cloud(int depth, const std::string& ns) {
  return {in_namespace(kCloud, ns), &sensor_msgs_msg_dds__PointCloud2__desc, cloud_qos(depth)};
}
Detections detections(const std::string& ns) {
  return {in_namespace(kDetections, ns), &rangefit_msgs_msg_dds__Detection__desc, result_qos()};
}
Detections detections_reader(const std::string& ns) {
  return {in_namespace(kDetections, ns), &rangefit_msgs_msg_dds__Detection__desc,
          result_reader_qos()};
}
Pose pose(const std::string& ns) {
  return {in_namespace(kPose, ns), &geometry_msgs_msg_dds__PoseStamped__desc, latched_qos()};
}
Poses poses(const std::string& ns) {
  return {in_namespace(kPoses, ns), &geometry_msgs_msg_dds__PoseArray__desc, latched_qos()};
}
State state(const std::string& ns) {
  return {in_namespace(kState, ns), &rangefit_msgs_msg_dds__State__desc, latched_qos()};
}
Models models(const std::string& ns) {
  return {in_namespace(kModels, ns), &rangefit_msgs_msg_dds__Models__desc, latched_qos()};
}
Diagnostics diagnostics() {
  return {kDiagnostics, &diagnostic_msgs_msg_dds__DiagnosticArray__desc, diagnostics_qos()};
}
Request request(int max_samples, const std::string& ns) {
  return {in_namespace(kRequest, ns), &rangefit_msgs_msg_dds__DetectRequest__desc,
          request_qos(max_samples)};
}
Tf tf() { return {kTf, &tf2_msgs_msg_dds__TFMessage__desc, tf_qos()}; }
Tf tf_static() { return {kTfStatic, &tf2_msgs_msg_dds__TFMessage__desc, tf_static_qos()}; }
Detections3d detections3d(const std::string& ns) {
  return {in_namespace(kDetections3d, ns), &vision_msgs_msg_dds__Detection3DArray__desc,
          latched_qos()};
}
Markers markers(const std::string& ns) {
  return {in_namespace(kMarkers, ns), &visualization_msgs_msg_dds__MarkerArray__desc,
          latched_qos()};
}

}  // namespace rangefit::daemon::topics
