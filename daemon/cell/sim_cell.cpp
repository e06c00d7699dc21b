#include "daemon/cell/sim_cell.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>

#include "daemon/cell/scan_loop.hpp"
#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"
#include "sim/css_simulator.hpp"
#include "sim/pan_tilt_head.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::daemon {
namespace {

using std::chrono::milliseconds;

hal::Duration seconds(double s) {
  return std::chrono::duration_cast<hal::Duration>(std::chrono::duration<double>(s));
}

hal::StreamCounters operator+(hal::StreamCounters a, const hal::StreamCounters& b) {
  a.samples += b.samples;
  a.dropped += b.dropped;
  a.gaps += b.gaps;
  a.crc_errors += b.crc_errors;
  a.resyncs += b.resyncs;
  a.timeouts += b.timeouts;
  a.faults += b.faults;
  a.reconnects += b.reconnects;
  return a;
}

bool scans(const DeviceConfig& d) {
  return d.kind == "css" || d.kind == "stripe" || d.kind == "pan_tilt";
}

// Symmetric sweeps only: the simulated CSS and head sweep -a .. +a about their centre.
bool half_sweep(const ScanRequest& r, double fallback, double* half, std::string* why) {
  if (r.sweep_start == r.sweep_end) {
    *half = fallback;
    return true;
  }
  if (!(r.sweep_end > r.sweep_start) || std::abs(r.sweep_start + r.sweep_end) > 1e-6) {
    *why = "sweep must be symmetric about the centre (-a .. +a rad), got " +
           std::to_string(r.sweep_start) + " .. " + std::to_string(r.sweep_end);
    return false;
  }
  *half = 0.5 * (r.sweep_end - r.sweep_start);
  return true;
}

}  // namespace

struct SimCell::LoadedScene {
  explicit LoadedScene(const std::string& path) : scene(sim::load_scene(path)), caster(scene) {}
  sim::Scene scene;
  sim::RayCaster caster;  // refers to scene: never moved
};

// One scan in progress: what the scan loops share.
struct SimCell::Run {
  SimCell& cell;
  const DeviceConfig& device;
  const ScanRequest& request;
  const std::atomic<bool>& cancel;
  const std::function<void()>& progress;
  const LoadedScene& scene;
  std::uint64_t seed;
  sim::FaultOptions sensor_faults;
  std::string motion_name;  // "<name>/joint", ...
  std::map<std::string, hal::StreamCounters> base;

  // Copies the devices' health for diagnostics; false (with *why) when one lost its link.
  bool watch(const hal::Device& sensor, const hal::Device& motion, std::string* why) {
    const hal::DeviceHealth hs = sensor.health();
    const hal::DeviceHealth hm = motion.health();
    {
      std::lock_guard lock(cell.mutex_);
      for (const auto& [name, h] : {std::pair{device.name, &hs}, {motion_name, &hm}}) {
        hal::DeviceHealth& out = cell.health_[name];
        out.state = h->state;
        out.counters = base[name] + h->counters;
        out.message = h->message;
      }
    }
    for (const auto* h : {&hs, &hm}) {
      if (h->state == hal::DeviceState::kDisconnected || h->state == hal::DeviceState::kFault) {
        *why = h->message.empty() ? std::string(hal::to_string(h->state)) : h->message;
        return false;
      }
    }
    return true;
  }

  // Ends the scan: stops the devices and keeps their counters; a failed scan leaves the
  // devices' last state (disconnected) for diagnostics, a good one leaves them ready.
  void end(hal::Device& sensor, hal::Device& motion, bool ok) {
    std::string ignored;
    watch(sensor, motion, &ignored);
    sensor.stop();
    motion.stop();
    std::lock_guard lock(cell.mutex_);
    for (const auto& name : {device.name, motion_name}) {
      if (ok) {
        cell.health_[name].state = hal::DeviceState::kReady;
        cell.health_[name].message.clear();
      }
      cell.totals_[name] = cell.health_[name].counters;
    }
  }

  ScanControl control() const { return {cancel, progress}; }
  // watch() as a scan loop's health check.
  auto healthy(const hal::Device& sensor, const hal::Device& motion) {
    return [this, &sensor, &motion](std::string* why) { return watch(sensor, motion, why); };
  }
};

SimCell::SimCell(const CellConfig& config)
    : SimCell(config, std::make_unique<sim::SimClock>(config.sim.time_scale)) {}

SimCell::SimCell(const CellConfig& config, std::unique_ptr<sim::SimClock> clock)
    : config_(config), clock_(std::move(clock)) {
  std::map<std::string, std::shared_ptr<LoadedScene>> by_path;
  for (const auto& d : config_.devices) {
    if (d.driver != DriverKind::kSim) continue;
    if (scans(d)) {
      auto& loaded = by_path[d.scene.string()];
      try {
        if (!loaded) loaded = std::make_shared<LoadedScene>(d.scene.string());
      } catch (const std::exception& e) {
        throw std::runtime_error("device " + d.name + ": scene " + d.scene.string() + ": " +
                                 e.what());
      }
      scenes_[d.name] = loaded;
    }
    health_[d.name].state = hal::DeviceState::kReady;
  }
}

SimCell::~SimCell() = default;

std::vector<NamedHealth> SimCell::health() const {
  std::lock_guard lock(mutex_);
  std::vector<NamedHealth> out;
  for (const auto& [name, h] : health_) out.push_back({name, h});
  return out;
}

ScanOutcome SimCell::scan(const DeviceConfig& device, const ScanRequest& request,
                          const std::atomic<bool>& cancel, const std::function<void()>& progress) {
  const auto it = scenes_.find(device.name);
  if (it == scenes_.end()) {
    return {hal::Status::Error("device " + device.name + " (kind " + device.kind +
                               ") cannot scan; name a css, stripe or pan_tilt device"),
            {}};
  }
  const int n = ++scans_[device.name];
  Run run{*this, device, request, cancel, progress, *it->second, config_.sim.seed + n, {}, {}, {}};
  const SimFaultConfig& f = device.sim_fault;
  if (f.disconnect_after_s >= 0.0 && (f.on_scan == 0 || f.on_scan == n)) {
    run.sensor_faults.disconnect_after = seconds(f.disconnect_after_s);
    run.sensor_faults.disconnect_for = seconds(f.disconnect_for_s);
  }
  {
    std::lock_guard lock(mutex_);
    for (const auto& [name, counters] : totals_) run.base[name] = counters;
  }
  if (device.kind == "css") return scan_css(run);
  if (device.kind == "stripe") return scan_stripe(run);
  return scan_pan_tilt(run);
}

ScanOutcome SimCell::scan_css(Run& run) {
  run.motion_name = run.device.name + "/joint";
  fusion::CssFusionConfig fc = config_.fusion.css;
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
  o.css_faults = run.sensor_faults;
  if (config_.sim.noise) o.css_faults.range_noise_sigma_mm = 0.06;  // thesis 4.2.1: 60 um
  sim::CssRig rig(run.scene.scene, run.scene.caster, o, *clock_);
  fc.expected_revolutions = static_cast<std::size_t>(rig.revolutions_in_scan()) + 8;
  fusion::CssAssembler assembler(fc);
  assembler.begin_scan();
  const auto fuse = [&assembler](const std::vector<hal::CssRevolution>& revs,
                                 const std::vector<hal::JointSample>& joints) {
    for (const auto& j : joints) assembler.add_joint(j);
    for (const auto& r : revs) assembler.add_revolution(r);
  };
  bool ok = static_cast<bool>(rig.css().start()) && static_cast<bool>(rig.joint().start());
  const hal::Timestamp end = rig.scan_end() + milliseconds(300);
  ok = ok && run_scan_loop(
                 rig.css(), rig.joint(), run.control(), [&] { return clock_->now() >= end; }, fuse,
                 run.healthy(rig.css(), rig.joint()), &why) == ScanLoopEnd::kDone;
  run.end(rig.css(), rig.joint(), ok);
  if (!ok) return {hal::Status::Error(run.device.name + ": " + why), {}};
  return finish_scan(run.device, assembler.finish(), run.scene.scene.mounts.T_scene_css,
                     css_sensor(fc.geometry), clock_.get());
}

ScanOutcome SimCell::scan_stripe(Run& run) {
  run.motion_name = run.device.name + "/axis";
  const fusion::StripeCellFusionConfig& fc = config_.fusion.stripe_cell;
  sim::StripeCellOptions o;
  o.geometry = fc.geometry;
  o.quantise = config_.sim.noise;
  o.seed = run.seed;
  o.ranger_faults = run.sensor_faults;
  double from = 0.0, to = o.geometry.axis_travel_mm;
  if (run.request.sweep_start != run.request.sweep_end) {
    from = run.request.sweep_start;
    to = run.request.sweep_end;
  }
  const double speed =
      run.request.sweep_speed > 0.0 ? run.request.sweep_speed : o.geometry.max_speed_mm_s;
  sim::StripeCell cell(run.scene.scene, run.scene.caster, o, *clock_);
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
  return finish_scan(run.device, assembler.finish(), run.scene.scene.mounts.T_scene_stripe,
                     stripe_sensor(fc.geometry, from, to), clock_.get());
}

ScanOutcome SimCell::scan_pan_tilt(Run& run) {
  run.motion_name = run.device.name + "/angles";
  fusion::PanTiltFusionConfig fc = config_.fusion.pan_tilt;
  double half = 0.0;
  std::string why;
  if (!half_sweep(run.request, 0.5 * fc.geometry.sweep_angle_rad, &half, &why)) {
    return {hal::Status::Error(run.device.name + ": " + why), {}};
  }
  fc.geometry.sweep_angle_rad = 2.0 * half;
  if (run.request.sweep_speed > 0.0) fc.geometry.sweep_rate_rad_s = run.request.sweep_speed;
  sim::PanTiltOptions o;
  o.geometry = fc.geometry;
  o.quantise = config_.sim.noise;
  o.seed = run.seed;
  o.ranger_faults = run.sensor_faults;
  sim::PanTiltHead head(run.scene.scene, run.scene.caster, o, *clock_);
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
                 [&] { return clock_->now() >= head.sweep_end(); }, fuse,
                 run.healthy(head.ranger(), head.angles()), &why) == ScanLoopEnd::kDone;
  run.end(head.ranger(), head.angles(), ok);
  if (!ok) return {hal::Status::Error(run.device.name + ": " + why), {}};
  return finish_scan(run.device, assembler.finish(), run.scene.scene.mounts.T_scene_pantilt,
                     pan_tilt_sensor(fc.geometry, half, o.tilt_rad), clock_.get());
}

}  // namespace rangefit::daemon
