// kind = "stripe", driver = "sim": sim::StripeCell ray-casts the device's scene: ranger profiles
// and the linear axis' samples ("<name>/axis") into the StripeCellAssembler, the axis moving to
// the sweep's start and then through it at the request's speed (thesis ch. 5).
#include "daemon/cell/sim_sensor.hpp"
#include "fusion/profile_assembler.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::daemon::sim_sensors {
namespace {

ScanOutcome stripe_scan(SimCell::Run& run) {
  run.motion_name = run.device.name + "/axis";
  // A further camera of the laser plane sees the cell from its own pose and side.
  const fusion::StripeCellFusionConfig fc =
      fusion::stripe_cell_for(run.config.fusion.stripe_cell, run.device.name);
  sim::StripeCellOptions o;
  o.geometry = fc.geometry;
  o.quantise = run.config.sim.noise;
  o.seed = run.seed;
  o.ranger_faults = run.sensor_faults;
  double from = 0.0, to = o.geometry.axis_travel_mm;
  if (run.request.sweep_start != run.request.sweep_end) {
    from = run.request.sweep_start;
    to = run.request.sweep_end;
  }
  const double speed =
      run.request.sweep_speed > 0.0 ? run.request.sweep_speed : o.geometry.max_speed_mm_s;
  sim::StripeCell cell(run.scene.scene, run.scene.caster, o, run.clock);
  fusion::StripeCellAssembler assembler(fc);
  hal::LinearAxis& axis = cell.axis();
  hal::RangerSource& ranger = cell.ranger();
  std::string why;
  hal::Status st = axis.enable();
  if (st) st = axis.start();
  // Move to the sweep's start first (not fused; the ranger is off meanwhile so no profile is
  // ray-cast in vain), then sweep at the requested speed.
  if (st && from != 0.0) st = axis.move_to(from, o.geometry.max_speed_mm_s);
  ScanLoopEnd end = ScanLoopEnd::kFailed;
  if (st) {
    const auto start_sweep = [&](std::string*) {
      assembler.begin_scan();
      st = ranger.start();
      if (st) st = axis.move_to(to, speed);
      return static_cast<bool>(st);
    };
    end = sweep_stripe(axis, ranger, assembler, run.control(), start_sweep,
                       run.healthy(ranger, axis), &why);
  }
  if (!st) why = "axis: " + st.message;
  const bool ok = end == ScanLoopEnd::kDone;
  run.end(ranger, axis, ok);
  if (!ok) return {hal::Status::Error(run.device.name + ": " + why), {}};
  return finish_scan(
      run.device, assembler.finish(), run.scene.scene.mounts.T_scene_stripe,
      stripe_sensor(fc.geometry, from, to,
                    fusion::stripe_camera_of(run.config.fusion.stripe_cell, run.device.name)),
      &run.clock);
}

}  // namespace

extern const SimSensor stripe;
const SimSensor stripe{"stripe", stripe_scan};

}  // namespace rangefit::daemon::sim_sensors
