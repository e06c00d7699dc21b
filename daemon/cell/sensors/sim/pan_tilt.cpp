// kind = "pan_tilt", driver = "sim": sim::PanTiltHead ray-casts the device's scene: ranger
// profiles and the head's pan/tilt samples ("<name>/angles") into the PanTiltAssembler, over a
// symmetric pan sweep at the request's rate (thesis 5.3). Further cameras of the head's laser
// plane scanning together ride the same sweep, each with its own ranger stream and assembler.
#include <memory>

#include "daemon/cell/sim_sensor.hpp"
#include "fusion/profile_assembler.hpp"
#include "sim/pan_tilt_head.hpp"

namespace rangefit::daemon::sim_sensors {
namespace {

std::vector<ScanOutcome> pan_tilt_sweep(SimCell::Run& run) {
  run.motion_name = run.device.name + "/angles";
  std::vector<const DeviceConfig*> devices = {&run.device};
  for (const auto& c : run.cameras) devices.push_back(c.device);
  const auto failed = [&](const std::string& why) {
    return std::vector<ScanOutcome>(
        devices.size(), ScanOutcome{hal::Status::Error(run.device.name + ": " + why), {}});
  };
  double half = 0.0;
  std::string why;
  const double configured = 0.5 * run.config.fusion.pan_tilt.geometry.sweep_angle_rad;
  if (!half_sweep(run.request, configured, &half, &why)) return failed(why);
  // Every camera of the laser plane sees the scene from its own side.
  std::vector<fusion::PanTiltFusionConfig> fcs;
  for (const DeviceConfig* d : devices) {
    fusion::PanTiltFusionConfig fc = fusion::pan_tilt_for(run.config.fusion.pan_tilt, d->name);
    fc.geometry.sweep_angle_rad = 2.0 * half;
    if (run.request.sweep_speed > 0.0) fc.geometry.sweep_rate_rad_s = run.request.sweep_speed;
    fcs.push_back(fc);
  }
  sim::PanTiltOptions o;
  o.geometry = fcs.front().geometry;
  o.quantise = run.config.sim.noise;
  o.seed = run.seed;
  // Standing in for the cell program: a calibration sweep is taken at the tilt the request says
  // the head is held at.
  if (run.request.kind == DetectKind::kCalibrate && run.request.target.tilt_rad) {
    o.tilt_rad = *run.request.target.tilt_rad;
  }
  o.ranger_faults = run.sensor_faults;
  for (std::size_t k = 0; k < run.cameras.size(); ++k) {
    o.cameras.push_back({fcs[k + 1].geometry.ranger, run.cameras[k].faults, run.cameras[k].seed});
  }
  sim::PanTiltHead head(run.scene.scene, run.scene.caster, o, run.clock);
  std::vector<std::unique_ptr<fusion::PanTiltAssembler>> assemblers;
  std::vector<hal::RangerSource*> rangers;
  for (std::size_t k = 0; k < devices.size(); ++k) {
    assemblers.push_back(std::make_unique<fusion::PanTiltAssembler>(fcs[k]));
    assemblers.back()->begin_scan();
    rangers.push_back(&head.ranger(k));
    if (k > 0) run.also.emplace_back(devices[k]->name, &head.ranger(k));
  }
  const auto fuse = [&assemblers](const std::vector<hal::PanTiltSample>& angles,
                                  std::span<const std::vector<hal::RangerProfile>> profiles) {
    for (std::size_t k = 0; k < assemblers.size(); ++k) {
      for (const auto& s : angles) assemblers[k]->add_pan_tilt(s);
      for (const auto& p : profiles[k]) assemblers[k]->add_profile(p);
    }
  };
  bool ok = static_cast<bool>(head.angles().start());
  for (hal::RangerSource* r : rangers) ok = ok && static_cast<bool>(r->start());
  ok = ok && run_scan_loop(
                 head.angles(), std::span<hal::RangerSource* const>(rangers), run.control(),
                 [&] { return run.clock.now() >= head.sweep_end(); }, fuse,
                 run.healthy(head.ranger(), head.angles()), &why) == ScanLoopEnd::kDone;
  run.end(head.ranger(), head.angles(), ok);
  if (!ok) return failed(why);
  std::vector<ScanOutcome> out;
  for (std::size_t k = 0; k < devices.size(); ++k) {
    out.push_back(finish_scan(*devices[k], assemblers[k]->finish(),
                              run.scene.scene.mounts.T_scene_pantilt,
                              pan_tilt_sensor(fcs[k].geometry, half, o.tilt_rad), &run.clock));
  }
  return out;
}

ScanOutcome pan_tilt_scan(SimCell::Run& run) { return std::move(pan_tilt_sweep(run).front()); }

}  // namespace

extern const SimSensor pan_tilt;
const SimSensor pan_tilt{"pan_tilt", pan_tilt_scan, pan_tilt_sweep};

}  // namespace rangefit::daemon::sim_sensors
