#include "daemon/service/device_extrinsics.hpp"
#include "hal/rpy.hpp"

namespace rangefit::daemon {

Eigen::Isometry3d device_extrinsics(const DeviceConfig& d) {
  return hal::pose_xyz_rpy(d.xyz_mm[0], d.xyz_mm[1], d.xyz_mm[2], d.rpy_rad[0], d.rpy_rad[1],
                           d.rpy_rad[2]);
}

std::vector<NamedTransform> sensor_mounts(const DaemonConfig& config) {
  std::vector<NamedTransform> out;
  for (const auto& d : config.devices) {
    out.push_back({config.frames.sensor(d.name), device_extrinsics(d)});
  }
  return out;
}

}  // namespace rangefit::daemon
