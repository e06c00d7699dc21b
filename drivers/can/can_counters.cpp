#include "drivers/can/can_counters.hpp"

namespace rangefit::drivers::can {

const char* to_string(Counter c) {
  static constexpr std::array<const char*, static_cast<std::size_t>(Counter::kCount)> kNames{
      "samples",     "ring_dropped", "gaps",       "crc_errors",    "timeouts",
      "faults",      "bus_errors",   "bus_off",    "error_passive", "restarts",
      "unknown_ids", "bad_lengths",  "duplicates", "reordered",     "reboots",
      "nodes_lost",  "link_downs",   "reconnects", "tx_buffer_full"};
  const auto i = static_cast<std::size_t>(c);
  return i < kNames.size() ? kNames[i] : "?";
}

CanCounters AtomicCanCounters::snapshot(const TransportCounters& transport) const {
  CanCounters c;
  for (std::size_t i = 0; i < c.values.size(); ++i) {
    c.values[i] = values_[i].load(std::memory_order_relaxed);
  }
  c.transport = transport;
  return c;
}

hal::StreamCounters CanCounters::stream() const {
  hal::StreamCounters s;
  s.samples = (*this)[Counter::kSamples];
  s.dropped = (*this)[Counter::kRingDropped] + transport.rx_overflow;
  s.gaps = (*this)[Counter::kGaps];
  s.crc_errors = (*this)[Counter::kCrcErrors];
  s.timeouts = (*this)[Counter::kTimeouts];
  s.faults = (*this)[Counter::kFaults] + (*this)[Counter::kBusOff];
  s.reconnects = (*this)[Counter::kReconnects];
  return s;
}

}  // namespace rangefit::drivers::can
