// kind = "pan_tilt", driver = "real": the head's ranger (drivers::can::RangerCanSource, node
// can_node) and its pan and tilt axes (drivers::can::Cia402PanTiltSource, nodes pan_node and
// tilt_node, reported as "<name>/angles") on one SocketCAN interface. Like the CSS it records
// while the cell program pans the head through the sweep (eq. 5.7; the daemon does not command
// the head). A further camera of the head's laser plane is a pan_tilt device whose `motion`
// names the head: it has only its ranger and records while the head's angles pass the sweep,
// with the head's own camera when a request names both.
#include <cmath>
#include <memory>

#include "daemon/cell/driver_configs.hpp"
#include "daemon/cell/real_devices.hpp"
#include "daemon/cell/real_sensor.hpp"
#include "fusion/profile_assembler.hpp"

namespace rangefit::daemon::real_sensors {
namespace {

std::vector<NamedDriver> pan_tilt_drivers(const DeviceConfig& d, const CellConfig& config,
                                          hal::Clock&) {
  std::vector<NamedDriver> out;
  out.push_back({d.name, ranger_driver(d, config.fusion.pan_tilt.geometry.ranger)});
  if (!d.motion.empty()) return out;  // a further camera: the head's angles are the other's
  const auto head = pan_tilt_config(d);
  out.push_back({pan_tilt_angles_name(d.name),
                 std::make_unique<drivers::can::Cia402PanTiltSource>(
                     head, socketcan(d.transport, drivers::can::cia402_filter(
                                                      drivers::can::pan_tilt_bus_config(head))))});
  return out;
}

// The health name of the angles that move the device's camera.
std::string head_of(const DeviceConfig& d) {
  return pan_tilt_angles_name(d.motion.empty() ? d.name : d.motion);
}

std::vector<ScanOutcome> pan_tilt_sweep(RealDevices& cell,
                                        std::span<const DeviceConfig* const> devices,
                                        const ScanRequest& request, ScanControl control) {
  const DeviceConfig& device = *devices.front();
  const std::string head_name = head_of(device);
  for (const DeviceConfig* d : devices.subspan(1)) {
    if (head_of(*d) != head_name) return {};  // not one head
  }
  std::string why;
  auto* head = cell.driver_as<hal::PanTiltSource>(head_name, &why);
  if (head == nullptr) return all_failed(devices, hal::Status::Error(why));
  std::vector<hal::RangerSource*> rangers;
  std::vector<std::unique_ptr<fusion::PanTiltAssembler>> assemblers;
  std::vector<std::function<bool(std::string*)>> watches;
  std::vector<fusion::PanTiltFusionConfig> fcs;
  for (const DeviceConfig* d : devices) {
    auto* ranger = cell.driver_as<hal::RangerSource>(d->name, &why);
    if (ranger == nullptr) return all_failed(devices, hal::Status::Error(why));
    if (hal::Status s = usable(d->name, *ranger, head_name, *head); !s)
      return all_failed(devices, s);
    fusion::PanTiltFusionConfig fc = fusion::pan_tilt_for(cell.config().fusion.pan_tilt, d->name);
    if (request.sweep_start != request.sweep_end) {
      fc.geometry.sweep_angle_rad = std::abs(request.sweep_end - request.sweep_start);
    }
    fcs.push_back(fc);
    rangers.push_back(ranger);
    assemblers.push_back(std::make_unique<fusion::PanTiltAssembler>(fc));
    assemblers.back()->begin_scan();
    watches.push_back(health_watch(d->name, *ranger, head_name, *head));
  }
  // Like the CSS: records while the cell program pans the head from -half to +half about
  // pan_zero (eq. 5.7); what arrived before the request is dropped first.
  for (hal::RangerSource* r : rangers) drop_stale(*r, *head);
  const hal::PanTiltGeometry& g = fcs.front().geometry;
  SweepEdges sweep{0.5 * g.sweep_angle_rad};
  const auto fuse = [&](const std::vector<hal::PanTiltSample>& angles,
                        std::span<const std::vector<hal::RangerProfile>> profiles) {
    for (const auto& a : angles) sweep.see(a.pan_rad - g.pan_zero_rad);
    for (std::size_t k = 0; k < assemblers.size(); ++k) {
      for (const auto& a : angles) assemblers[k]->add_pan_tilt(a);
      for (const auto& p : profiles[k]) assemblers[k]->add_profile(p);
    }
  };
  const auto healthy = all_healthy(std::move(watches));
  const ScanLoopEnd end = run_scan_loop(
      *head, std::span<hal::RangerSource* const>(rangers), control, [&] { return sweep.at_end; },
      fuse, healthy, &why);
  if (end != ScanLoopEnd::kDone) return all_failed(devices, failed(device, why).status);
  // The real head's tilt is held by the cell program; its zero is the calibrated pose.
  std::vector<ScanOutcome> out;
  for (std::size_t k = 0; k < devices.size(); ++k) {
    out.push_back(finish_scan(
        *devices[k], assemblers[k]->finish(), Eigen::Isometry3d::Identity(),
        pan_tilt_sensor(fcs[k].geometry, 0.5 * g.sweep_angle_rad, g.tilt_zero_rad), &cell.clock()));
  }
  return out;
}

ScanOutcome pan_tilt_scan(RealDevices& cell, const DeviceConfig& device, const ScanRequest& request,
                          ScanControl control) {
  const DeviceConfig* const one[] = {&device};
  return std::move(pan_tilt_sweep(cell, one, request, control).front());
}

}  // namespace

extern const RealSensor pan_tilt;
const RealSensor pan_tilt{"pan_tilt", pan_tilt_drivers, pan_tilt_scan, pan_tilt_sweep};

}  // namespace rangefit::daemon::real_sensors
