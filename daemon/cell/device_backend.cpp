#include "daemon/cell/device_backend.hpp"

#include "daemon/cell/real_devices.hpp"
#ifdef RANGEFIT_WITH_SIM
#include "daemon/cell/sim_cell.hpp"
#endif

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
  const DeviceConfig* device = config_.device(request.sensor);
  if (device == nullptr) return {hal::Status::Error("unknown sensor " + request.sensor), {}};
  if (cancel) return {hal::Status::Error("cancelled"), {}};
  if (device->driver == DriverKind::kReplay) return replay(*device, progress);
#ifdef RANGEFIT_WITH_SIM
  if (device->driver == DriverKind::kSim) return sim_->scan(*device, request, cancel, progress);
#endif
  return real_->scan(*device, request, cancel, progress);
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
