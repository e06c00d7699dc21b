#include "daemon/cell/sim_cell.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>

#include "daemon/cell/sim_sensor.hpp"
#include "sim/scene_loader.hpp"

namespace rangefit::daemon {
namespace {

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

}  // namespace

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

const SimSensor* find_sim_sensor(const DeviceKind& kind) {
  for (const SimSensor* s : all_sim_sensors()) {
    if (kind.name() == s->kind) return s;
  }
  return nullptr;
}

SimCell::LoadedScene::LoadedScene(const std::string& path)
    : scene(sim::load_scene(path)), caster(scene) {}

bool SimCell::Run::watch(const hal::Device& sensor, const hal::Device& motion, std::string* why) {
  std::vector<std::pair<std::string, hal::DeviceHealth>> seen = {{device.name, sensor.health()},
                                                                 {motion_name, motion.health()}};
  for (const auto& [name, d] : also) seen.emplace_back(name, d->health());
  {
    std::lock_guard lock(cell.mutex_);
    for (const auto& [name, h] : seen) {
      hal::DeviceHealth& out = cell.health_[name];
      out.state = h.state;
      out.counters = base[name] + h.counters;
      out.message = h.message;
    }
  }
  for (const auto& [name, h] : seen) {
    if (h.state == hal::DeviceState::kDisconnected || h.state == hal::DeviceState::kFault) {
      const std::string what = h.message.empty() ? std::string(hal::to_string(h.state)) : h.message;
      // The run's own sensor and motion are named by the caller's error; a further camera here.
      *why = name == device.name || name == motion_name ? what : name + ": " + what;
      return false;
    }
  }
  return true;
}

void SimCell::Run::end(hal::Device& sensor, hal::Device& motion, bool ok) {
  std::string ignored;
  watch(sensor, motion, &ignored);
  sensor.stop();
  motion.stop();
  std::vector<std::string> names = {device.name, motion_name};
  for (const auto& [name, d] : also) {
    d->stop();
    names.push_back(name);
  }
  std::lock_guard lock(cell.mutex_);
  for (const auto& name : names) {
    if (ok) {
      cell.health_[name].state = hal::DeviceState::kReady;
      cell.health_[name].message.clear();
    }
    cell.totals_[name] = cell.health_[name].counters;
  }
}

SimCell::SimCell(const CellConfig& config)
    : SimCell(config, std::make_unique<sim::SimClock>(config.sim.time_scale)) {}

SimCell::SimCell(const CellConfig& config, std::unique_ptr<sim::SimClock> clock)
    : config_(config), clock_(std::move(clock)) {
  std::map<std::string, std::shared_ptr<LoadedScene>> by_path;
  for (const auto& d : config_.devices) {
    if (d.driver != DriverKind::kSim) continue;
    if (find_sim_sensor(d.kind) != nullptr) {  // a sensor: it scans the scene
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

SimCell::Run SimCell::start_run(const DeviceConfig& device, const ScanRequest& request,
                                const std::atomic<bool>& cancel,
                                const std::function<void()>& progress, const LoadedScene& scene) {
  auto [seed, faults] = next_scan(device);
  Run run{*this,  device, request, cancel,  progress, scene, seed,
          faults, {},     {},      config_, *clock_,  {},    {}};
  std::lock_guard lock(mutex_);
  for (const auto& [name, counters] : totals_) run.base[name] = counters;
  return run;
}

std::pair<std::uint64_t, sim::FaultOptions> SimCell::next_scan(const DeviceConfig& device) {
  const int n = ++scans_[device.name];
  sim::FaultOptions faults;
  const SimFaultConfig& f = device.sim_fault;
  if (f.disconnect_after_s >= 0.0 && (f.on_scan == 0 || f.on_scan == n)) {
    faults.disconnect_after = seconds(f.disconnect_after_s);
    faults.disconnect_for = seconds(f.disconnect_for_s);
  }
  return {config_.sim.seed + static_cast<std::uint64_t>(n), faults};
}

ScanOutcome SimCell::scan(const DeviceConfig& device, const ScanRequest& request,
                          const std::atomic<bool>& cancel, const std::function<void()>& progress) {
  const auto it = scenes_.find(device.name);
  const SimSensor* kind = find_sim_sensor(device.kind);
  if (it == scenes_.end() || kind == nullptr) {
    const std::string sensors =
        sensor_kind_names([](const SensorKind& k) { return find_sim_sensor(k) != nullptr; });
    return {
        hal::Status::Error("device " + device.name + " (kind " + std::string(device.kind.name()) +
                           ") cannot scan; name a " + sensors + " device"),
        {}};
  }
  Run run = start_run(device, request, cancel, progress, *it->second);
  return kind->scan(run);
}

std::vector<ScanOutcome> SimCell::scan_together(std::span<const DeviceConfig* const> devices,
                                                const ScanRequest& request,
                                                const std::atomic<bool>& cancel,
                                                const std::function<void()>& progress) {
  if (devices.size() < 2) return {};
  const DeviceConfig& first = *devices.front();
  const SimSensor* kind = find_sim_sensor(first.kind);
  const auto scene = scenes_.find(first.name);
  if (kind == nullptr || kind->scan_together == nullptr || scene == scenes_.end()) return {};
  for (const DeviceConfig* d : devices.subspan(1)) {
    // One simulated cell: the same scene.
    const auto other = scenes_.find(d->name);
    if (other == scenes_.end() || other->second != scene->second) return {};
  }
  Run run = start_run(first, request, cancel, progress, *scene->second);
  for (const DeviceConfig* d : devices.subspan(1)) {
    auto [s, f] = next_scan(*d);
    run.cameras.push_back({d, s, f});
  }
  return kind->scan_together(run);
}

}  // namespace rangefit::daemon
