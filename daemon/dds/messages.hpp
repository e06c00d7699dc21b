#pragma once
// Conversions between rangefitd's C++ values (mm, rad, Eigen) and the idlc-generated ROS 2 wire
// structs (SI metres, REP-103). Outgoing messages are built into *Out objects that own the
// storage the C struct points into; they are neither copied nor moved (the pointers would dangle).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "daemon/service/lifecycle.hpp"
#include "daemon/service/scan_types.hpp"
#include "detect/common/point_cloud.hpp"
#include "diagnostic_msgs.h"
#include "rangefit_msgs.h"
#include "sensor_msgs.h"

namespace rangefit::daemon {

// std_msgs/Header stamp from the wall clock (ROS time), as ROS 2 nodes expect.
builtin_interfaces_msg_dds__Time_ wall_time_now();
builtin_interfaces_msg_dds__Time_ wall_time(std::int64_t ns_since_epoch);

class CloudOut {
 public:
  // x, y, z as FLOAT32 metres (plus normal_x/y/z when the cloud has normals); unorganised.
  // frame: the header's frame id; empty: the cloud's own.
  explicit CloudOut(const PointCloud& cloud, const std::string& frame = "");
  CloudOut(const CloudOut&) = delete;
  CloudOut& operator=(const CloudOut&) = delete;
  const sensor_msgs_msg_dds__PointCloud2_& msg() const { return msg_; }

 private:
  std::string frame_;
  std::vector<std::string> names_;
  std::vector<sensor_msgs_msg_dds__PointField_> fields_;
  std::vector<std::uint8_t> data_;
  sensor_msgs_msg_dds__PointCloud2_ msg_{};
};

// Reads x, y, z (FLOAT32 or FLOAT64, either byte order as flagged) back into mm. Returns an
// empty cloud with frame_id set when the message lacks x/y/z or its sizes are inconsistent.
PointCloud from_msg(const sensor_msgs_msg_dds__PointCloud2_& msg);

class DetectionOut {
 public:
  explicit DetectionOut(const DetectionResult& r, std::string frame = "world");
  DetectionOut(const DetectionOut&) = delete;
  DetectionOut& operator=(const DetectionOut&) = delete;
  const rangefit_msgs_msg_dds__Detection_& msg() const { return msg_; }
  // Header stamp: the scan's acquisition time when known (acquired_wall_ns), else now.
  // The pose of the first part as geometry_msgs/PoseStamped (rt/rangefit/pose).
  geometry_msgs_msg_dds__PoseStamped_ first_pose() const;

 private:
  DetectionResult r_;
  std::string frame_, kind_, details_;
  std::vector<char*> names_;
  std::vector<geometry_msgs_msg_dds__Pose_> poses_;
  std::vector<double> scores_;
  std::vector<std::uint32_t> instances_;
  rangefit_msgs_msg_dds__Detection_ msg_{};
};
DetectionResult from_msg(const rangefit_msgs_msg_dds__Detection_& msg);

class RequestOut {
 public:
  explicit RequestOut(const ScanRequest& req, bool linear_sweep);
  RequestOut(const RequestOut&) = delete;
  RequestOut& operator=(const RequestOut&) = delete;
  const rangefit_msgs_msg_dds__DetectRequest_& msg() const { return msg_; }

 private:
  ScanRequest req_;
  std::string kind_, walls_, target_;
  std::vector<char*> sensors_;  // into req_.sensors
  std::vector<char*> scans_;    // into req_.target.scans
  rangefit_msgs_msg_dds__DetectRequest_ msg_{};
};

// Decodes a request; on a malformed one (unknown kind, non-finite numbers) returns the reason in
// *error and a request carrying at least the id. Zero vectors and counts are "not given". Sweep
// values are converted with linear_sweep (metres → mm) only once the sensor is known, see
// convert_sweep_units().
ScanRequest from_msg(const rangefit_msgs_msg_dds__DetectRequest_& msg, std::string* error);

class StateOut {
 public:
  StateOut(LifecycleState s, std::string detail, std::string active_id, std::uint32_t depth,
           std::string frame = "world");
  StateOut(const StateOut&) = delete;
  StateOut& operator=(const StateOut&) = delete;
  const rangefit_msgs_msg_dds__State_& msg() const { return msg_; }

 private:
  std::string frame_, detail_, active_;
  rangefit_msgs_msg_dds__State_ msg_{};
};

class DiagnosticsOut {
 public:
  explicit DiagnosticsOut(std::vector<DiagStatus> statuses);
  DiagnosticsOut(const DiagnosticsOut&) = delete;
  DiagnosticsOut& operator=(const DiagnosticsOut&) = delete;
  const diagnostic_msgs_msg_dds__DiagnosticArray_& msg() const { return msg_; }

 private:
  std::string frame_;
  std::vector<DiagStatus> statuses_;
  std::vector<std::vector<diagnostic_msgs_msg_dds__KeyValue_>> values_;
  std::vector<diagnostic_msgs_msg_dds__DiagnosticStatus_> c_statuses_;
  diagnostic_msgs_msg_dds__DiagnosticArray_ msg_{};
};
std::vector<DiagStatus> from_msg(const diagnostic_msgs_msg_dds__DiagnosticArray_& msg);

}  // namespace rangefit::daemon
