#include "daemon/cell/real_devices.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "daemon/cell/real_sensor.hpp"

namespace rangefit::daemon {

RealDevices::RealDevices(const CellConfig& config)
    : config_(config), clock_(std::make_unique<hal::MonotonicClock>()) {
  for (const auto& d : config_.devices) {
    if (d.driver != DriverKind::kReal) continue;
    const RealSensor* kind = find_real_sensor(d.kind);
    if (kind == nullptr) continue;
    for (auto& [name, driver] : kind->make_drivers(d, config_, *clock_)) {
      if (!driver) continue;
      if (const hal::Status s = driver->start(); !s) {
        throw std::runtime_error("device " + name + ": " + s.message);
      }
      spdlog::info("device {}: {} driver on {} started", name, d.kind.name(), d.transport);
      drivers_of_[d.name].push_back(name);
      devices_[name] = std::move(driver);
    }
  }
}

RealDevices::~RealDevices() {
  for (auto& [name, d] : devices_) d->stop();
}

std::vector<NamedHealth> RealDevices::health() const {
  std::vector<NamedHealth> out;
  for (const auto& d : config_.devices) {
    if (d.driver != DriverKind::kReal) continue;
    const auto it = drivers_of_.find(d.name);
    if (it == drivers_of_.end()) {
      hal::DeviceHealth h;
      h.message = "no real driver for kind " + std::string(d.kind.name()) + " in this build";
      out.push_back({d.name, h});
      continue;
    }
    for (const std::string& name : it->second) out.push_back({name, devices_.at(name)->health()});
  }
  return out;
}

hal::Device* RealDevices::motion_of(const DeviceConfig& device, std::string* why) const {
  const DeviceKind kind(device.kind->moved_by);
  std::string name = device.motion;
  if (name.empty()) {
    for (const auto& d : config_.devices) {
      if (d.kind != kind || d.driver != DriverKind::kReal) continue;
      if (!name.empty()) {
        *why =
            device.name + ": several " + std::string(kind.name()) + " devices; set devices.motion";
        return nullptr;
      }
      name = d.name;
    }
  }
  const auto it = devices_.find(name);
  if (name.empty() || it == devices_.end()) {
    *why =
        device.name + ": no real " + std::string(kind.name()) + " device moves it (devices.motion)";
    return nullptr;
  }
  return it->second.get();
}

ScanOutcome RealDevices::scan(const DeviceConfig& device, const ScanRequest& request,
                              const std::atomic<bool>& cancel,
                              const std::function<void()>& progress) {
  const RealSensor* kind = find_real_sensor(device.kind);
  if (kind == nullptr || kind->scan == nullptr) {
    return {
        hal::Status::Error("device " + device.name + " (kind " + std::string(device.kind.name()) +
                           ") cannot scan with driver = \"real\" in this build"),
        {}};
  }
  return kind->scan(*this, device, request, {cancel, progress});
}

std::vector<ScanOutcome> RealDevices::scan_together(std::span<const DeviceConfig* const> devices,
                                                    const ScanRequest& request,
                                                    const std::atomic<bool>& cancel,
                                                    const std::function<void()>& progress) {
  if (devices.size() < 2) return {};
  const DeviceConfig& first = *devices.front();
  const RealSensor* kind = find_real_sensor(first.kind);
  if (kind == nullptr || kind->scan_together == nullptr) return {};
  return kind->scan_together(*this, devices, request, {cancel, progress});
}

}  // namespace rangefit::daemon
