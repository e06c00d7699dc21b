// kind = "pan_tilt", driver = "real": the head's ranger (drivers::can::RangerCanSource, node
// can_node) and its pan and tilt axes (drivers::can::Cia402PanTiltSource, nodes pan_node and
// tilt_node, reported as "<name>/angles") on one SocketCAN interface. Like the CSS it records
// while the cell program pans the head through the sweep (eq. 5.7; the daemon does not command
// the head).
#include <cmath>

#include "daemon/cell/driver_configs.hpp"
#include "daemon/cell/real_devices.hpp"
#include "daemon/cell/real_sensor.hpp"
#include "fusion/profile_assembler.hpp"

namespace rangefit::daemon::real_sensors {
namespace {

std::vector<NamedDriver> pan_tilt_drivers(const DeviceConfig& d, const CellConfig& config,
                                          hal::Clock&) {
  const auto head = pan_tilt_config(d);
  std::vector<NamedDriver> out;
  out.push_back({d.name, ranger_driver(d, config.fusion.pan_tilt.geometry.ranger)});
  out.push_back({pan_tilt_angles_name(d.name),
                 std::make_unique<drivers::can::Cia402PanTiltSource>(
                     head, socketcan(d.transport, drivers::can::cia402_filter(
                                                      drivers::can::pan_tilt_bus_config(head))))});
  return out;
}

ScanOutcome pan_tilt_scan(RealDevices& cell, const DeviceConfig& device, const ScanRequest& request,
                          ScanControl control) {
  const std::string head_name = pan_tilt_angles_name(device.name);
  std::string why;
  auto* ranger = cell.driver_as<hal::RangerSource>(device.name, &why);
  auto* head = ranger ? cell.driver_as<hal::PanTiltSource>(head_name, &why) : nullptr;
  if (head == nullptr) return {hal::Status::Error(why), {}};
  if (hal::Status s = usable(device.name, *ranger, head_name, *head); !s) return {s, {}};
  fusion::PanTiltFusionConfig fc = cell.config().fusion.pan_tilt;
  if (request.sweep_start != request.sweep_end) {
    fc.geometry.sweep_angle_rad = std::abs(request.sweep_end - request.sweep_start);
  }
  fusion::PanTiltAssembler assembler(fc);
  assembler.begin_scan();
  // Like the CSS: records while the cell program pans the head from -half to +half about
  // pan_zero (eq. 5.7); what arrived before the request is dropped first.
  drop_stale(*ranger, *head);
  SweepEdges sweep{0.5 * fc.geometry.sweep_angle_rad};
  const auto fuse = [&](const std::vector<hal::PanTiltSample>& angles,
                        const std::vector<hal::RangerProfile>& profiles) {
    for (const auto& a : angles) {
      sweep.see(a.pan_rad - fc.geometry.pan_zero_rad);
      assembler.add_pan_tilt(a);
    }
    for (const auto& p : profiles) assembler.add_profile(p);
  };
  const ScanLoopEnd end = run_scan_loop(
      *head, *ranger, control, [&] { return sweep.at_end; }, fuse,
      health_watch(device.name, *ranger, head_name, *head), &why);
  if (end != ScanLoopEnd::kDone) return failed(device, why);
  // The real head's tilt is held by the cell program; its zero is the calibrated pose.
  return finish_scan(
      device, assembler.finish(), Eigen::Isometry3d::Identity(),
      pan_tilt_sensor(fc.geometry, 0.5 * fc.geometry.sweep_angle_rad, fc.geometry.tilt_zero_rad),
      &cell.clock());
}

}  // namespace

extern const RealSensor pan_tilt;
const RealSensor pan_tilt{"pan_tilt", pan_tilt_drivers, pan_tilt_scan};

}  // namespace rangefit::daemon::real_sensors
