#include "daemon/cell/device_backend.hpp"

#include "daemon/cell/fuse_views.hpp"
#include "daemon/cell/real_devices.hpp"
#ifdef RANGEFIT_WITH_SIM
#include "daemon/cell/sim_cell.hpp"
#endif

#include <algorithm>
#include <stdexcept>

#include "io/ply.hpp"

namespace rangefit::daemon {

DeviceBackend::DeviceBackend(CellConfig config) : config_(std::move(config)) {
  for (const auto& d : config_.devices) {
    if (d.driver == DriverKind::kSim) {
#ifdef RANGEFIT_WITH_SIM
      if (!sim_) sim_ = std::make_unique<SimCell>(config_);
#else
      throw std::runtime_error("device '" + d.name +
                               "': driver = \"sim\", but this rangefitd was built without the "
                               "simulated cell (RANGEFIT_WITH_SIM=OFF)");
#endif
    } else if (d.driver == DriverKind::kReal) {
      if (!real_) real_ = std::make_unique<RealDevices>(config_);
    } else {
      health_[d.name].state = hal::DeviceState::kReady;
    }
  }
}

std::vector<NamedHealth> DeviceBackend::health() const {
  std::lock_guard lock(mutex_);
  std::vector<NamedHealth> out;
  for (const auto& [name, h] : health_) out.push_back({name, h});
#ifdef RANGEFIT_WITH_SIM
  if (sim_) {
    for (auto& h : sim_->health()) out.push_back(std::move(h));
  }
#endif
  if (real_) {
    for (auto& h : real_->health()) out.push_back(std::move(h));
  }
  return out;
}

ScanOutcome DeviceBackend::scan(const ScanRequest& request, const std::atomic<bool>& cancel,
                                const std::function<void()>& progress) {
  if (request.sensors.size() > 1) return scan_views(request, cancel, progress);
  const DeviceConfig* device = config_.device(request.sensor);
  if (device == nullptr) return {hal::Status::Error("unknown sensor " + request.sensor), {}};
  if (cancel) return {hal::Status::Error("cancelled"), {}};
  if (device->driver == DriverKind::kReplay) return replay(*device, progress);
#ifdef RANGEFIT_WITH_SIM
  if (device->driver == DriverKind::kSim) return sim_->scan(*device, request, cancel, progress);
#endif
  return real_->scan(*device, request, cancel, progress);
}

// One scan per sensor, each over its configured sweep (validation refuses a sweep override with
// several sensors), fused into one cloud (fuse_views). Devices that can scan together do (the
// cameras of one laser plane on one axis or head: one sweep for all); others scan in turn, in
// order, until one fails. The request's scan timeout covers all the scans.
ScanOutcome DeviceBackend::scan_views(const ScanRequest& request, const std::atomic<bool>& cancel,
                                      const std::function<void()>& progress) {
  std::vector<const DeviceConfig*> devices;
  for (const std::string& name : request.sensors) {
    const DeviceConfig* device = config_.device(name);
    if (device == nullptr) return {hal::Status::Error("unknown sensor " + name), {}};
    devices.push_back(device);
  }
  if (cancel) return {hal::Status::Error("cancelled"), {}};
  const auto one_request = [&](const DeviceConfig& device) {
    ScanRequest one = request;
    one.sensors.clear();
    one.sensor = device.name;
    one.sweep_start = device.sweep_start;
    one.sweep_end = device.sweep_end;
    one.sweep_speed = device.sweep_speed;
    return one;
  };
  const DeviceConfig& first = *devices.front();
  const bool alike = std::all_of(devices.begin(), devices.end(), [&](const DeviceConfig* d) {
    return d->driver == first.driver && d->kind == first.kind &&
           d->sweep_start == first.sweep_start && d->sweep_end == first.sweep_end &&
           d->sweep_speed == first.sweep_speed;
  });
  CellDevices* cell = nullptr;
#ifdef RANGEFIT_WITH_SIM
  if (alike && first.driver == DriverKind::kSim) cell = sim_.get();
#endif
  if (alike && first.driver == DriverKind::kReal) cell = real_.get();
  std::vector<ScanOutcome> views;
  if (cell != nullptr) views = cell->scan_together(devices, one_request(first), cancel, progress);
  const bool together = !views.empty();
  for (std::size_t k = 0; !together && k < devices.size(); ++k) {
    views.push_back(scan(one_request(*devices[k]), cancel, progress));
    if (!views.back().status) break;
  }
  // A shared sweep's error names the devices already. A stripe calibration solves each camera
  // on its own sweep: the views go apart too.
  return fuse_views(views, request.sensors,
                    {.cameras = request.kind == DetectKind::kObject,
                     .named = together,
                     .keep_apart = request.kind == DetectKind::kCalibrate});
}

ScanOutcome DeviceBackend::replay(const DeviceConfig& device,
                                  const std::function<void()>& progress) {
  std::lock_guard lock(mutex_);
  auto& health = health_[device.name];
  auto it = replay_cache_.find(device.name);
  if (it == replay_cache_.end()) {
    try {
      it = replay_cache_.emplace(device.name, io::read_ply(device.replay_file)).first;
    } catch (const std::exception& e) {
      // The file may come back (e.g. a mount); the next request retries.
      health.state = hal::DeviceState::kDisconnected;
      health.message = e.what();
      ++health.counters.timeouts;
      return {hal::Status::Error(device.name + ": " + e.what()), {}};
    }
  }
  progress();
  health.state = hal::DeviceState::kReady;
  health.message.clear();
  health.counters.samples += it->second.size();
  return {hal::Status::Ok(), it->second};
}

}  // namespace rangefit::daemon
