// kind = "pan_tilt", driver = "sim": sim::PanTiltHead ray-casts the device's scene: ranger
// profiles and the head's pan/tilt samples ("<name>/angles") into the PanTiltAssembler, over a
// symmetric pan sweep at the request's rate (thesis 5.3).
#include "daemon/cell/sim_sensor.hpp"
#include "fusion/profile_assembler.hpp"
#include "sim/pan_tilt_head.hpp"

namespace rangefit::daemon::sim_sensors {
namespace {

ScanOutcome pan_tilt_scan(SimCell::Run& run) {
  run.motion_name = run.device.name + "/angles";
  fusion::PanTiltFusionConfig fc = run.config.fusion.pan_tilt;
  double half = 0.0;
  std::string why;
  if (!half_sweep(run.request, 0.5 * fc.geometry.sweep_angle_rad, &half, &why)) {
    return {hal::Status::Error(run.device.name + ": " + why), {}};
  }
  fc.geometry.sweep_angle_rad = 2.0 * half;
  if (run.request.sweep_speed > 0.0) fc.geometry.sweep_rate_rad_s = run.request.sweep_speed;
  sim::PanTiltOptions o;
  o.geometry = fc.geometry;
  o.quantise = run.config.sim.noise;
  o.seed = run.seed;
  // Standing in for the cell program: a calibration sweep is taken at the tilt the request says
  // the head is held at.
  if (run.request.kind == DetectKind::kCalibrate && run.request.target.tilt_rad) {
    o.tilt_rad = *run.request.target.tilt_rad;
  }
  o.ranger_faults = run.sensor_faults;
  sim::PanTiltHead head(run.scene.scene, run.scene.caster, o, run.clock);
  fusion::PanTiltAssembler assembler(fc);
  assembler.begin_scan();
  const auto fuse = [&assembler](const std::vector<hal::PanTiltSample>& angles,
                                 const std::vector<hal::RangerProfile>& profiles) {
    for (const auto& s : angles) assembler.add_pan_tilt(s);
    for (const auto& p : profiles) assembler.add_profile(p);
  };
  bool ok = static_cast<bool>(head.angles().start()) && static_cast<bool>(head.ranger().start());
  ok = ok && run_scan_loop(
                 head.angles(), head.ranger(), run.control(),
                 [&] { return run.clock.now() >= head.sweep_end(); }, fuse,
                 run.healthy(head.ranger(), head.angles()), &why) == ScanLoopEnd::kDone;
  run.end(head.ranger(), head.angles(), ok);
  if (!ok) return {hal::Status::Error(run.device.name + ": " + why), {}};
  return finish_scan(run.device, assembler.finish(), run.scene.scene.mounts.T_scene_pantilt,
                     pan_tilt_sensor(fc.geometry, half, o.tilt_rad), &run.clock);
}

}  // namespace

extern const SimSensor pan_tilt;
const SimSensor pan_tilt{"pan_tilt", pan_tilt_scan};

}  // namespace rangefit::daemon::sim_sensors
