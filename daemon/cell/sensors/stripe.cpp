// kind = "stripe", driver = "real": the laser-stripe ranger on CAN (drivers::can::RangerCanSource,
// node can_node, default 0x20, on a SocketCAN interface). It sweeps with its `motion` axis (or
// the only axis) exactly like the simulated cell: to the sweep's start, then through it. Further
// cameras of the laser plane on the same axis sweep with it: the axis moves once, and each
// camera's profiles go to its own assembler.
#include <memory>

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

std::vector<ScanOutcome> stripe_sweep(RealDevices& cell,
                                      std::span<const DeviceConfig* const> devices,
                                      const ScanRequest& request, ScanControl control) {
  const DeviceConfig& device = *devices.front();
  std::string why;
  auto* axis = cell.motion_as<hal::LinearAxis>(device, &why);
  if (axis == nullptr) return all_failed(devices, hal::Status::Error(why));
  for (const DeviceConfig* d : devices.subspan(1)) {
    if (cell.motion_as<hal::LinearAxis>(*d, &why) != axis) return {};  // not one axis
  }
  const std::string axis_name = axis->name();
  std::vector<hal::RangerSource*> rangers;
  std::vector<fusion::StripeCellFusionConfig> fcs;
  for (const DeviceConfig* d : devices) {
    auto* ranger = cell.driver_as<hal::RangerSource>(d->name, &why);
    if (ranger == nullptr) return all_failed(devices, hal::Status::Error(why));
    if (hal::Status s = usable(d->name, *ranger, axis_name, *axis); !s) {
      return all_failed(devices, s);
    }
    rangers.push_back(ranger);
    fcs.push_back(fusion::stripe_cell_for(cell.config().fusion.stripe_cell, d->name));
  }
  const hal::StripeCellGeometry& g = fcs.front().geometry;
  double from = 0.0, to = g.axis_travel_mm;
  if (request.sweep_start != request.sweep_end) {
    from = request.sweep_start;
    to = request.sweep_end;
  }
  const double speed = request.sweep_speed > 0.0 ? request.sweep_speed : g.max_speed_mm_s;
  std::vector<std::unique_ptr<fusion::StripeCellAssembler>> assemblers;
  std::vector<StripeCamera> cameras;
  std::vector<std::function<bool(std::string*)>> watches;
  for (std::size_t k = 0; k < devices.size(); ++k) {
    assemblers.push_back(std::make_unique<fusion::StripeCellAssembler>(fcs[k]));
    cameras.push_back({rangers[k], assemblers.back().get()});
    watches.push_back(health_watch(devices[k]->name, *rangers[k], axis_name, *axis));
  }
  hal::Status st = axis->enable();
  if (st) st = axis->move_to(from, g.max_speed_mm_s);
  if (!st) return all_failed(devices, failed(device, axis_name + ": " + st.message).status);
  const auto start_sweep = [&](std::string* w) {
    for (const StripeCamera& c : cameras) c.assembler->begin_scan();
    const hal::Status s = axis->move_to(to, speed);
    if (!s) *w = axis_name + ": " + s.message;
    return static_cast<bool>(s);
  };
  const auto healthy = all_healthy(std::move(watches));
  const ScanLoopEnd end = sweep_stripe(*axis, cameras, control, start_sweep, healthy, &why);
  if (end == ScanLoopEnd::kCancelled) {
    // The operator must know when the axis could not be stopped: it may still be moving.
    if (const hal::Status halted = axis->halt(); !halted) why += "; halt failed: " + halted.message;
  }
  if (end != ScanLoopEnd::kDone) return all_failed(devices, failed(device, why).status);
  std::vector<ScanOutcome> out;
  for (std::size_t k = 0; k < devices.size(); ++k) {
    out.push_back(finish_scan(
        *devices[k], assemblers[k]->finish(), Eigen::Isometry3d::Identity(),
        stripe_sensor(fcs[k].geometry, from, to,
                      fusion::stripe_camera_of(cell.config().fusion.stripe_cell, devices[k]->name)),
        &cell.clock()));
  }
  return out;
}

ScanOutcome stripe_scan(RealDevices& cell, const DeviceConfig& device, const ScanRequest& request,
                        ScanControl control) {
  const DeviceConfig* const one[] = {&device};
  return std::move(stripe_sweep(cell, one, request, control).front());
}

}  // namespace

extern const RealSensor stripe;
const RealSensor stripe{"stripe", stripe_drivers, stripe_scan, stripe_sweep};

}  // namespace rangefit::daemon::real_sensors
