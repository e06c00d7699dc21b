// kind = "css", driver = "sim": sim::CssRig ray-casts the device's scene: CSS revolutions and
// the robot's last-joint stream ("<name>/joint") into the CssAssembler, over a symmetric sweep
// -delta .. +delta at the request's joint rate (thesis 4.2; noise: 60 um, 4.2.1).
#include <chrono>

#include "daemon/cell/sim_sensor.hpp"
#include "fusion/css_assembler.hpp"
#include "sim/css_simulator.hpp"

namespace rangefit::daemon::sim_sensors {
namespace {

ScanOutcome css_scan(SimCell::Run& run) {
  run.motion_name = run.device.name + "/joint";
  fusion::CssFusionConfig fc = run.config.fusion.css;
  std::string why;
  if (!half_sweep(run.request, fc.deflection_rad, &fc.deflection_rad, &why)) {
    return {hal::Status::Error(run.device.name + ": " + why), {}};
  }
  // The request's speed is the joint's angular rate; the CSS model wants the TCP speed (4.21).
  if (run.request.sweep_speed > 0.0) {
    fc.scan_speed_mm_s = run.request.sweep_speed * fc.geometry.pivot_radius_mm;
  }
  sim::CssScanOptions o;
  o.geometry = fc.geometry;
  o.deflection_rad = fc.deflection_rad;
  o.speed_mm_s = fc.scan_speed_mm_s;
  o.joint_id = fc.joint;
  o.seed = run.seed;
  // Standing in for the robot program: a CSS calibration scan is taken where the request says
  // the robot holds the joint (the scene's frame being the robot base).
  const CalibrationTarget& target = run.request.target;
  if (run.request.kind == DetectKind::kCalibrate && target.T_base_joint) {
    o.T_scene_world = *target.T_base_joint;
  }
  o.css_faults = run.sensor_faults;
  if (run.config.sim.noise) o.css_faults.range_noise_sigma_mm = 0.06;  // thesis 4.2.1: 60 um
  sim::CssRig rig(run.scene.scene, run.scene.caster, o, run.clock);
  fc.expected_revolutions = static_cast<std::size_t>(rig.revolutions_in_scan()) + 8;
  fusion::CssAssembler assembler(fc);
  assembler.begin_scan();
  const auto fuse = [&assembler](const std::vector<hal::CssRevolution>& revs,
                                 const std::vector<hal::JointSample>& joints) {
    for (const auto& j : joints) assembler.add_joint(j);
    for (const auto& r : revs) assembler.add_revolution(r);
  };
  bool ok = static_cast<bool>(rig.css().start()) && static_cast<bool>(rig.joint().start());
  const hal::Timestamp end = rig.scan_end() + std::chrono::milliseconds(300);
  ok = ok && run_scan_loop(
                 rig.css(), rig.joint(), run.control(), [&] { return run.clock.now() >= end; },
                 fuse, run.healthy(rig.css(), rig.joint()), &why) == ScanLoopEnd::kDone;
  run.end(rig.css(), rig.joint(), ok);
  if (!ok) return {hal::Status::Error(run.device.name + ": " + why), {}};
  return finish_scan(run.device, assembler.finish(),
                     o.T_scene_world.value_or(run.scene.scene.mounts.T_scene_css),
                     css_sensor(fc.geometry, fc.omega_zero_rad), &run.clock);
}

}  // namespace

extern const SimSensor css;
const SimSensor css{"css", css_scan};

}  // namespace rangefit::daemon::sim_sensors
