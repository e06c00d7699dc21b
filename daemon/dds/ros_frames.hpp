#pragma once
// rangefitd's results as a ROS 2 tool stack reads them: tf2 frames (tf2_msgs/TFMessage on
// rt/tf_static for the sensors' mounts, on rt/tf for every detected part) and
// geometry_msgs/PoseArray of every part (rt/rangefit/poses). SI metres, frames from [frames].
// Like messages.hpp, each *Out owns the storage its C struct points into.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "daemon/service/config.hpp"
#include "daemon/service/device_extrinsics.hpp"
#include "daemon/service/scan_types.hpp"
#include "geometry_msgs.h"
#include "tf2_msgs.h"

namespace rangefit::daemon {

// A pose in mm as geometry_msgs/Pose in metres.
geometry_msgs_msg_dds__Pose_ pose_in_metres(const Eigen::Isometry3d& T);

// The frame a detected part is published as: "rangefit/<model or bore>/<part>/<instance>".
std::string part_frame(const DetectionResult& result, const PartPose& part);
// Every part of a found result as a frame below the world frame, each id after `prefix` (the
// ROS namespace's "cell1/").
std::vector<NamedTransform> part_frames(const DetectionResult& result,
                                        const std::string& prefix = "");

class TfOut {
 public:
  TfOut(const builtin_interfaces_msg_dds__Time_& stamp, std::string parent,
        std::vector<NamedTransform> transforms);
  TfOut(const TfOut&) = delete;
  TfOut& operator=(const TfOut&) = delete;
  const tf2_msgs_msg_dds__TFMessage_& msg() const { return msg_; }

 private:
  std::string parent_;
  std::vector<NamedTransform> named_;
  std::vector<geometry_msgs_msg_dds__TransformStamped_> transforms_;
  tf2_msgs_msg_dds__TFMessage_ msg_{};
};

class PoseArrayOut {
 public:
  PoseArrayOut(const DetectionResult& result, std::string frame);
  PoseArrayOut(const PoseArrayOut&) = delete;
  PoseArrayOut& operator=(const PoseArrayOut&) = delete;
  const geometry_msgs_msg_dds__PoseArray_& msg() const { return msg_; }

 private:
  std::string frame_;
  std::vector<geometry_msgs_msg_dds__Pose_> poses_;
  geometry_msgs_msg_dds__PoseArray_ msg_{};
};

// The header stamp of a result: the scan's acquisition time when known, else now.
builtin_interfaces_msg_dds__Time_ result_stamp(const DetectionResult& result);

}  // namespace rangefit::daemon
