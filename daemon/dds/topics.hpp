#pragma once
// rangefitd's topics, written once for the daemon (dds_service.hpp) and its clients (client.hpp)
// so both sides always match. All ROS 2-compatible (rt/ prefix, <pkg>::msg::dds_::<Name>_ types,
// XCDR1):
//   rt/rangefit/cloud           sensor_msgs/PointCloud2     reliable, volatile, keep last 2
//   rt/rangefit/detections      rangefit_msgs/Detection     reliable, transient-local (last 1),
//                               keep-all (1024): every answer reaches every matched reader
//   rt/rangefit/pose            geometry_msgs/PoseStamped   reliable, transient-local, depth 1
//   rt/rangefit/poses           geometry_msgs/PoseArray     every part; reliable, transient-local
//   rt/rangefit/detections3d    vision_msgs/Detection3DArray  every part; reliable, transient-local
//   rt/rangefit/markers         visualization_msgs/MarkerArray  a mesh per part; reliable,
//                               transient-local (matches rviz2's reliable, volatile reader)
//   rt/rangefit/state           rangefit_msgs/State         reliable, transient-local, depth 1
//   rt/rangefit/models          rangefit_msgs/Models        reliable, transient-local, depth 1
//   rt/diagnostics              diagnostic_msgs/DiagnosticArray  reliable, volatile, depth 10
//   rt/tf                       tf2_msgs/TFMessage          every part as a frame; depth 100
//   rt/tf_static                tf2_msgs/TFMessage          the sensors' mounts; transient-local
//   rt/rangefit/detect_request  rangefit_msgs/DetectRequest (read)  reliable, volatile, keep-all
//                               (dds.request_depth unread requests; beyond, the sender resends)
//   rq/rangefit/detectRequest, rr/rangefit/detectReply: the ROS 2 service (ros_service.hpp)
// With a ROS namespace ([ros] namespace = "cell1") every rangefit/ topic and the service move
// below it (rt/cell1/rangefit/cloud, rq/cell1/rangefit/detectRequest), as a node started in
// that namespace publishes its relative names; rt/tf, rt/tf_static and rt/diagnostics stay
// global as tf2 and diagnostic_updater use them, their frame ids prefixed "cell1/" instead.

#include "daemon/dds/dds.hpp"
#include "diagnostic_msgs.h"
#include "geometry_msgs.h"
#include "rangefit_msgs.h"
#include "sensor_msgs.h"
#include "tf2_msgs.h"
#include "vision_msgs.h"
#include "visualization_msgs.h"

namespace rangefit::daemon::topics {

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
inline constexpr const char* kDetections3d = "rt/rangefit/detections3d";
inline constexpr const char* kMarkers = "rt/rangefit/markers";

// The DDS name of a ROS 2 topic or service topic (rt/..., rq/..., rr/...) of the default
// namespace moved into `ns` ("cell1", "plant/cell1"; empty: unchanged).
std::string in_namespace(const char* name, const std::string& ns);

using Cloud = dds::Topic<sensor_msgs_msg_dds__PointCloud2_>;
using Detections = dds::Topic<rangefit_msgs_msg_dds__Detection_>;
using Pose = dds::Topic<geometry_msgs_msg_dds__PoseStamped_>;
using State = dds::Topic<rangefit_msgs_msg_dds__State_>;
using Diagnostics = dds::Topic<diagnostic_msgs_msg_dds__DiagnosticArray_>;
using Request = dds::Topic<rangefit_msgs_msg_dds__DetectRequest_>;
using Poses = dds::Topic<geometry_msgs_msg_dds__PoseArray_>;
using Models = dds::Topic<rangefit_msgs_msg_dds__Models_>;
using Tf = dds::Topic<tf2_msgs_msg_dds__TFMessage_>;
using Detections3d = dds::Topic<vision_msgs_msg_dds__Detection3DArray_>;
using Markers = dds::Topic<visualization_msgs_msg_dds__MarkerArray_>;

// ns: the ROS namespace (see in_namespace); the global topics take none.
Cloud cloud(int depth = 2, const std::string& ns = "");
Detections detections(const std::string& ns = "");         // the daemon's writer: keep-all
Detections detections_reader(const std::string& ns = "");  // clients: keep-all, deeper
Pose pose(const std::string& ns = "");
Poses poses(const std::string& ns = "");
State state(const std::string& ns = "");
Models models(const std::string& ns = "");
Diagnostics diagnostics();
// Keep-all up to max_samples unread requests.
Request request(int max_samples = 64, const std::string& ns = "");
Tf tf();         // tf2's dynamic broadcaster: reliable, volatile, depth 100
Tf tf_static();  // tf2's static broadcaster: reliable, transient-local, depth 1
Detections3d detections3d(const std::string& ns = "");
Markers markers(const std::string& ns = "");

// The QoS alone (benchmarks and tests that open a topic by hand).
dds::QosSpec cloud_qos(int depth = 2);
dds::QosSpec latched_qos();  // pose, poses, state, models, detections3d, markers
dds::QosSpec diagnostics_qos();
dds::QosSpec request_qos(int max_samples = 64);
dds::QosSpec result_qos();         // rt/rangefit/detections, the daemon's writer
dds::QosSpec result_reader_qos();  // rt/rangefit/detections, the clients' reader
dds::QosSpec tf_qos();
dds::QosSpec tf_static_qos();

// Writer and reader of a topic row: topics::Writer<topics::Cloud>.
template <class Row>
struct Types;
template <class T>
struct Types<dds::Topic<T>> {
  using Writer = dds::Writer<T>;
  using Reader = dds::Reader<T>;
};
template <class Row>
using Writer = typename Types<Row>::Writer;
template <class Row>
using Reader = typename Types<Row>::Reader;

}  // namespace rangefit::daemon::topics
