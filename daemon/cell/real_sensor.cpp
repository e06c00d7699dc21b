#include "daemon/cell/real_sensor.hpp"

#include <string_view>

#include "daemon/cell/driver_configs.hpp"
#include "drivers/can/ranger_source.hpp"
#include "drivers/can/socketcan_transport.hpp"

namespace rangefit::daemon {

const RealSensor* find_real_sensor(const DeviceKind& kind) {
  for (const RealSensor* s : all_real_sensors()) {
    if (kind.name() == s->kind) return s;
  }
  return nullptr;
}

hal::Status usable(const std::string& a, const hal::Device& da, const std::string& b,
                   const hal::Device& db) {
  for (const auto& [name, dev] : {std::pair{&a, &da}, {&b, &db}}) {
    const hal::DeviceHealth h = dev->health();
    if (h.state == hal::DeviceState::kReady || h.state == hal::DeviceState::kStreaming) continue;
    return hal::Status::Error(*name + " not available (" + hal::to_string(h.state) +
                              (h.message.empty() ? "" : ": " + h.message) + ")");
  }
  return {};
}

std::function<bool(std::string*)> health_watch(const std::string& a, const hal::Device& da,
                                               const std::string& b, const hal::Device& db) {
  return [&a, &da, &b, &db](std::string* why) {
    for (const auto& [name, dev] : {std::pair{&a, &da}, {&b, &db}}) {
      const hal::DeviceHealth h = dev->health();
      if (h.state == hal::DeviceState::kDisconnected || h.state == hal::DeviceState::kFault) {
        *why = *name + ": " + (h.message.empty() ? hal::to_string(h.state) : h.message);
        return false;
      }
    }
    return true;
  };
}

ScanOutcome failed(const DeviceConfig& device, const std::string& why) {
  return {hal::Status::Error(device.name + ": " + why), {}};
}

std::vector<ScanOutcome> all_failed(std::span<const DeviceConfig* const> devices,
                                    const hal::Status& status) {
  return std::vector<ScanOutcome>(devices.size(), ScanOutcome{status, {}});
}

std::function<bool(std::string*)> all_healthy(
    std::vector<std::function<bool(std::string*)>> watches) {
  return [watches = std::move(watches)](std::string* why) {
    for (const auto& watch : watches) {
      if (!watch(why)) return false;
    }
    return true;
  };
}

std::unique_ptr<drivers::can::CanTransport> socketcan(const std::string& interface,
                                                      drivers::can::FrameFilter filter, bool fd) {
  drivers::can::SocketCanConfig c;
  c.interface = interface;
  c.filter = std::move(filter);
  c.fd = fd;
  return std::make_unique<drivers::can::SocketCanTransport>(c);
}

std::unique_ptr<hal::Device> ranger_driver(const DeviceConfig& d,
                                           const hal::StripeRanger& geometry) {
  const drivers::can::RangerConfig c = ranger_config(d, geometry);
  // The ranger's profiles are CAN FD frames: a classic socket never sees them.
  return std::make_unique<drivers::can::RangerCanSource>(
      c, socketcan(d.transport, drivers::can::ranger_filter(c), true));
}

}  // namespace rangefit::daemon
