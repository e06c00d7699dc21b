#include "daemon/cell/scan_loop.hpp"

#include <algorithm>

namespace rangefit::daemon {

std::int64_t wall_ns(hal::Timestamp t, const hal::Clock& clock) {
  const auto wall = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::system_clock::now().time_since_epoch());
  return (wall - (clock.now() - t)).count();
}

ScanOutcome finish_scan(const DeviceConfig& device, fusion::FusedScan scan,
                        const Eigen::Isometry3d& T_mount_sensor, const ScanSensor& sensor,
                        const hal::Clock* clock) {
  if (scan.bad) return {hal::Status::Error(device.name + ": fusion: " + scan.reason), {}};
  const Eigen::Isometry3d T = device_extrinsics(device) * T_mount_sensor;
  for (auto& p : scan.cloud.points) p = T * p;
  for (auto& n : scan.cloud.normals) n = T.linear() * n;
  ScanOutcome out{hal::Status::Ok(), std::move(scan.cloud), transformed(sensor, T), 0};
  if (out.sensor.pan_tilt) {  // the poses a calibration takes the profiles back with
    out.sensor.row_poses.reserve(scan.frames.size());
    for (const auto& f : scan.frames) out.sensor.row_poses.push_back(f.pose);
  }
  out.cloud.sensor = out.sensor.view;  // spooled and replayed with the cloud
  if (clock != nullptr && !out.cloud.stamps.empty()) {
    const hal::Timestamp last = *std::max_element(out.cloud.stamps.begin(), out.cloud.stamps.end());
    out.acquired_wall_ns = wall_ns(last, *clock);
  }
  return out;
}

}  // namespace rangefit::daemon
