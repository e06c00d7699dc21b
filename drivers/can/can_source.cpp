#include "drivers/can/can_source.hpp"

#include <spdlog/spdlog.h>

namespace rangefit::drivers::can {

bool open_for_start(CanTransport& transport, const std::string& name) {
  const hal::Status open = transport.reopen();
  if (!open) spdlog::warn("{}: {} (retrying)", name, open.message);
  return open.ok;
}

hal::DeviceHealth compose_health(bool started, const CanLoop& loop, bool devices_faulted,
                                 Problem problem, std::uint8_t node, const CanCounters& counters) {
  hal::DeviceHealth h;
  h.counters = counters.stream();
  const bool bus_off = loop.bus_off();
  if (!started)
    h.state = hal::DeviceState::kReady;
  else if (!loop.link_up())
    h.state = hal::DeviceState::kDisconnected;
  else if (bus_off || devices_faulted)
    h.state = hal::DeviceState::kFault;
  else
    h.state = hal::DeviceState::kStreaming;
  // The controller's current state outranks the last device problem while it lasts.
  if (started && loop.link_up() && bus_off) {
    problem = Problem::kBusOff;
    node = 0;
  }
  if (problem != Problem::kNone) {
    h.message = to_string(problem);
    if (node != 0) h.message += " (node " + std::to_string(node) + ")";
  }
  if (const Problem rt = loop.realtime_problem(); rt != Problem::kNone) {
    h.message += (h.message.empty() ? "" : "; ") + std::string(to_string(rt));
  }
  return h;
}

}  // namespace rangefit::drivers::can
