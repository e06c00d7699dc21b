#pragma once
// rangefitd's topics, written once for the daemon (dds_service.hpp) and its clients (client.hpp)
// so both sides always match. All ROS 2-compatible (rt/ prefix, <pkg>::msg::dds_::<Name>_ types,
// XCDR1):
//   rt/rangefit/cloud           sensor_msgs/PointCloud2     reliable, volatile, keep last 2
//   rt/rangefit/detections      rangefit_msgs/Detection     reliable, transient-local, depth 1
//   rt/rangefit/pose            geometry_msgs/PoseStamped   reliable, transient-local, depth 1
//   rt/rangefit/state           rangefit_msgs/State         reliable, transient-local, depth 1
//   rt/diagnostics              diagnostic_msgs/DiagnosticArray  reliable, volatile, depth 10
//   rt/rangefit/detect_request  rangefit_msgs/DetectRequest (read)  reliable, volatile

#include "daemon/dds/dds.hpp"
#include "diagnostic_msgs.h"
#include "geometry_msgs.h"
#include "rangefit_msgs.h"
#include "sensor_msgs.h"

namespace rangefit::daemon::topics {

inline constexpr const char* kCloud = "rt/rangefit/cloud";
inline constexpr const char* kDetections = "rt/rangefit/detections";
inline constexpr const char* kPose = "rt/rangefit/pose";
inline constexpr const char* kState = "rt/rangefit/state";
inline constexpr const char* kDiagnostics = "rt/diagnostics";
inline constexpr const char* kRequest = "rt/rangefit/detect_request";

using Cloud = dds::Topic<sensor_msgs_msg_dds__PointCloud2_>;
using Detections = dds::Topic<rangefit_msgs_msg_dds__Detection_>;
using Pose = dds::Topic<geometry_msgs_msg_dds__PoseStamped_>;
using State = dds::Topic<rangefit_msgs_msg_dds__State_>;
using Diagnostics = dds::Topic<diagnostic_msgs_msg_dds__DiagnosticArray_>;
using Request = dds::Topic<rangefit_msgs_msg_dds__DetectRequest_>;

// depth: keep-last history; a reader may keep more than the writer (a client catching up).
Cloud cloud(int depth = 2);
Detections detections(int depth = 1);
Pose pose();
State state();
Diagnostics diagnostics();
Request request(int depth = 16);

// The QoS alone (benchmarks and tests that open a topic by hand).
dds::QosSpec cloud_qos(int depth = 2);
dds::QosSpec latched_qos(int depth = 1);  // detections, pose, state
dds::QosSpec diagnostics_qos();
dds::QosSpec request_qos(int depth = 16);

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
