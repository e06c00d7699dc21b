#pragma once
// Where a device sits in the world frame, from its configured mount ([[devices]] xyz_mm, rpy_rad):
// the cell applies it to every scan, the DDS layer publishes it on /tf_static.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "daemon/service/config.hpp"

namespace rangefit::daemon {

// T(xyz_mm, rpy_rad) of a device: roll about x, then pitch about y, then yaw about z (fixed axes).
Eigen::Isometry3d device_extrinsics(const DeviceConfig& d);

struct NamedTransform {
  std::string child_frame;
  Eigen::Isometry3d T_parent_child = Eigen::Isometry3d::Identity();  // translation in mm
};

// The mount of every device: world frame -> the device's frame (FramesConfig::sensor).
std::vector<NamedTransform> sensor_mounts(const DaemonConfig& config);

}  // namespace rangefit::daemon
