#pragma once
// driver = "sim": what differs per kind of sensor. Each file of daemon/cell/sensors/sim/ (built
// only with RANGEFIT_WITH_SIM) registers one SimSensor (docs/adding_a_sensor.md): how the
// simulated devices of its kind scan the device's scene. SimCell looks them up by the device's
// kind, loads the scene of every device that has one, and hands each scan a Run.

#include <atomic>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "daemon/cell/scan_loop.hpp"
#include "daemon/cell/sim_cell.hpp"
#include "sim/fault_options.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scene.hpp"
#include "sim/sim_clock.hpp"

namespace rangefit::daemon {

struct SimCell::LoadedScene {
  explicit LoadedScene(const std::string& path);
  sim::Scene scene;
  sim::RayCaster caster;  // refers to scene: never moved
};

// One scan in progress: what a kind's scan needs of the cell.
struct SimCell::Run {
  SimCell& cell;
  const DeviceConfig& device;
  const ScanRequest& request;
  const std::atomic<bool>& cancel;
  const std::function<void()>& progress;
  const LoadedScene& scene;
  std::uint64_t seed;               // of this scan's noise and faults
  sim::FaultOptions sensor_faults;  // [devices.sim_fault] when it applies to this scan
  std::string motion_name;          // set by the scan: "<name>/joint", "/axis", "/angles"
  std::map<std::string, hal::StreamCounters> base;
  const CellConfig& config;
  sim::SimClock& clock;
  // Further devices scanning with this one in the same motion (scan_together): their own seeds
  // and faults. The scan adds their HAL devices to `also` so that watch() and end() cover them.
  struct Camera {
    const DeviceConfig* device;
    std::uint64_t seed;
    sim::FaultOptions faults;
  };
  std::vector<Camera> cameras;
  std::vector<std::pair<std::string, hal::Device*>> also;

  // Copies the devices' health for diagnostics; false (with *why) when one lost its link.
  bool watch(const hal::Device& sensor, const hal::Device& motion, std::string* why);
  // Ends the scan: stops the devices and keeps their counters; a failed scan leaves the
  // devices' last state (disconnected) for diagnostics, a good one leaves them ready.
  void end(hal::Device& sensor, hal::Device& motion, bool ok);

  ScanControl control() const { return {cancel, progress}; }
  // watch() as a scan loop's health check.
  auto healthy(const hal::Device& sensor, const hal::Device& motion) {
    return [this, &sensor, &motion](std::string* why) { return watch(sensor, motion, why); };
  }
};

struct SimSensor {
  const char* kind;  // SensorKind::name of the kind it simulates
  ScanOutcome (*scan)(SimCell::Run& run);
  // The run's device and run.cameras in one motion, one outcome each in that order; null when
  // the kind scans one device at a time.
  std::vector<ScanOutcome> (*scan_together)(SimCell::Run& run) = nullptr;
};

// Every registered SimSensor, in name order (generated from the files of daemon/cell/sensors/sim).
std::span<const SimSensor* const> all_sim_sensors();
// The SimSensor of that kind; null when there is none (a device that does not scan).
const SimSensor* find_sim_sensor(const DeviceKind& kind);

// Symmetric sweeps only: the simulated CSS and head sweep -a .. +a about their centre. *half is
// the request's half sweep, or `fallback` when it sets none; false (with *why) when asymmetric.
bool half_sweep(const ScanRequest& r, double fallback, double* half, std::string* why);

}  // namespace rangefit::daemon
