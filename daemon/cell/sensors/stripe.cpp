// kind = "stripe", driver = "real": the laser-stripe ranger on CAN (drivers::can::RangerCanSource,
// node can_node, default 0x20, on a SocketCAN interface). It sweeps with its `motion` axis (or
// the only axis) exactly like the simulated cell: to the sweep's start, then through it.
#include "daemon/cell/real_devices.hpp"
#include "daemon/cell/real_sensor.hpp"
#include "fusion/profile_assembler.hpp"

namespace rangefit::daemon::real_sensors {
namespace {

std::vector<NamedDriver> stripe_drivers(const DeviceConfig& d, const CellConfig& config,
                                        hal::Clock&) {
  std::vector<NamedDriver> out;
  out.push_back({d.name, ranger_driver(d, config.fusion.stripe_cell.geometry.ranger)});
  return out;
}

ScanOutcome stripe_scan(RealDevices& cell, const DeviceConfig& device, const ScanRequest& request,
                        ScanControl control) {
  std::string why;
  auto* axis = cell.motion_as<hal::LinearAxis>(device, &why);
  auto* ranger = axis ? cell.driver_as<hal::RangerSource>(device.name, &why) : nullptr;
  if (ranger == nullptr) return {hal::Status::Error(why), {}};
  const std::string axis_name = axis->name();
  if (hal::Status s = usable(device.name, *ranger, axis_name, *axis); !s) return {s, {}};
  const fusion::StripeCellFusionConfig fc =
      fusion::stripe_cell_for(cell.config().fusion.stripe_cell, device.name);
  double from = 0.0, to = fc.geometry.axis_travel_mm;
  if (request.sweep_start != request.sweep_end) {
    from = request.sweep_start;
    to = request.sweep_end;
  }
  const double speed = request.sweep_speed > 0.0 ? request.sweep_speed : fc.geometry.max_speed_mm_s;
  fusion::StripeCellAssembler assembler(fc);
  hal::Status st = axis->enable();
  if (st) st = axis->move_to(from, fc.geometry.max_speed_mm_s);
  if (!st) return failed(device, axis_name + ": " + st.message);
  const auto start_sweep = [&](std::string* w) {
    assembler.begin_scan();
    const hal::Status s = axis->move_to(to, speed);
    if (!s) *w = axis_name + ": " + s.message;
    return static_cast<bool>(s);
  };
  const ScanLoopEnd end = sweep_stripe(*axis, *ranger, assembler, control, start_sweep,
                                       health_watch(device.name, *ranger, axis_name, *axis), &why);
  if (end == ScanLoopEnd::kCancelled) {
    // The operator must know when the axis could not be stopped: it may still be moving.
    if (const hal::Status halted = axis->halt(); !halted) why += "; halt failed: " + halted.message;
  }
  if (end != ScanLoopEnd::kDone) return failed(device, why);
  return finish_scan(
      device, assembler.finish(), Eigen::Isometry3d::Identity(),
      stripe_sensor(fc.geometry, from, to,
                    fusion::stripe_camera_of(cell.config().fusion.stripe_cell, device.name)),
      &cell.clock());
}

}  // namespace

extern const RealSensor stripe;
const RealSensor stripe{"stripe", stripe_drivers, stripe_scan};

}  // namespace rangefit::daemon::real_sensors
