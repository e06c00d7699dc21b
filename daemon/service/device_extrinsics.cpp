#include "daemon/service/device_extrinsics.hpp"

namespace rangefit::daemon {

Eigen::Isometry3d device_extrinsics(const DeviceConfig& d) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(d.xyz_mm[0], d.xyz_mm[1], d.xyz_mm[2]);
  T.linear() = (Eigen::AngleAxisd(d.rpy_rad[2], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(d.rpy_rad[1], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(d.rpy_rad[0], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

std::vector<NamedTransform> sensor_mounts(const DaemonConfig& config) {
  std::vector<NamedTransform> out;
  for (const auto& d : config.devices) {
    out.push_back({config.frames.sensor(d.name), device_extrinsics(d)});
  }
  return out;
}

}  // namespace rangefit::daemon
