#include "daemon/scan_loop.hpp"

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

ScanOutcome finish_scan(const DeviceConfig& device, fusion::FusedScan scan,
                        const Eigen::Isometry3d& T_mount_sensor) {
  if (scan.bad) return {hal::Status::Error(device.name + ": fusion: " + scan.reason), {}};
  const Eigen::Isometry3d T = device_extrinsics(device) * T_mount_sensor;
  for (auto& p : scan.cloud.points) p = T * p;
  for (auto& n : scan.cloud.normals) n = T.linear() * n;
  return {hal::Status::Ok(), std::move(scan.cloud)};
}

}  // namespace rangefit::daemon
