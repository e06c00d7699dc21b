// kind = "stripe", driver = "sim": sim::StripeCell ray-casts the device's scene: ranger profiles
// and the linear axis' samples ("<name>/axis") into the StripeCellAssembler, the axis moving to
// the sweep's start and then through it at the request's speed (thesis ch. 5). Further cameras
// of the laser plane scanning together ride the same axis motion, each with its own ranger
// stream and assembler.
#include <memory>

#include "daemon/cell/sim_sensor.hpp"
#include "fusion/profile_assembler.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::daemon::sim_sensors {
namespace {

std::vector<ScanOutcome> stripe_sweep(SimCell::Run& run) {
  run.motion_name = run.device.name + "/axis";
  // Every camera of the laser plane sees the cell from its own pose and side.
  std::vector<const DeviceConfig*> devices = {&run.device};
  for (const auto& c : run.cameras) devices.push_back(c.device);
  std::vector<fusion::StripeCellFusionConfig> fcs;
  for (const DeviceConfig* d : devices) {
    fcs.push_back(fusion::stripe_cell_for(run.config.fusion.stripe_cell, d->name));
  }
  sim::StripeCellOptions o;
  o.geometry = fcs.front().geometry;
  o.quantise = run.config.sim.noise;
  o.seed = run.seed;
  o.ranger_faults = run.sensor_faults;
  for (std::size_t k = 0; k < run.cameras.size(); ++k) {
    o.cameras.push_back({fcs[k + 1].geometry, run.cameras[k].faults, run.cameras[k].seed});
  }
  double from = 0.0, to = o.geometry.axis_travel_mm;
  if (run.request.sweep_start != run.request.sweep_end) {
    from = run.request.sweep_start;
    to = run.request.sweep_end;
  }
  const double speed =
      run.request.sweep_speed > 0.0 ? run.request.sweep_speed : o.geometry.max_speed_mm_s;
  sim::StripeCell cell(run.scene.scene, run.scene.caster, o, run.clock);
  std::vector<std::unique_ptr<fusion::StripeCellAssembler>> assemblers;
  std::vector<StripeCamera> cameras;
  for (std::size_t k = 0; k < devices.size(); ++k) {
    assemblers.push_back(std::make_unique<fusion::StripeCellAssembler>(fcs[k]));
    cameras.push_back({&cell.ranger(k), assemblers.back().get()});
    if (k > 0) run.also.emplace_back(devices[k]->name, &cell.ranger(k));
  }
  hal::LinearAxis& axis = cell.axis();
  hal::RangerSource& ranger = cell.ranger();
  std::string why;
  hal::Status st = axis.enable();
  if (st) st = axis.start();
  // Move to the sweep's start first (not fused; the rangers are off meanwhile so no profile is
  // ray-cast in vain), then sweep at the requested speed.
  if (st && from != 0.0) st = axis.move_to(from, o.geometry.max_speed_mm_s);
  ScanLoopEnd end = ScanLoopEnd::kFailed;
  if (st) {
    const auto start_sweep = [&](std::string*) {
      for (const StripeCamera& c : cameras) {
        c.assembler->begin_scan();
        if (st) st = c.ranger->start();
      }
      if (st) st = axis.move_to(to, speed);
      return static_cast<bool>(st);
    };
    end = sweep_stripe(axis, cameras, run.control(), start_sweep, run.healthy(ranger, axis), &why);
  }
  if (!st) why = "axis: " + st.message;
  const bool ok = end == ScanLoopEnd::kDone;
  run.end(ranger, axis, ok);
  std::vector<ScanOutcome> out;
  for (std::size_t k = 0; k < devices.size(); ++k) {
    if (!ok) {
      out.push_back({hal::Status::Error(run.device.name + ": " + why), {}});
      continue;
    }
    out.push_back(finish_scan(
        *devices[k], assemblers[k]->finish(), run.scene.scene.mounts.T_scene_stripe,
        stripe_sensor(fcs[k].geometry, from, to,
                      fusion::stripe_camera_of(run.config.fusion.stripe_cell, devices[k]->name)),
        &run.clock));
  }
  return out;
}

ScanOutcome stripe_scan(SimCell::Run& run) { return std::move(stripe_sweep(run).front()); }

}  // namespace

extern const SimSensor stripe;
const SimSensor stripe{"stripe", stripe_scan, stripe_sweep};

}  // namespace rangefit::daemon::sim_sensors
