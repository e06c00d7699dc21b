#pragma once
// Counters every CAN driver keeps, beyond the HAL's StreamCounters: one atomic per kind, bumped
// from the receive thread without locks; snapshot() from any thread.

#include <array>
#include <atomic>
#include <cstdint>

#include "drivers/can/transport.hpp"
#include "hal/device.hpp"

namespace rangefit::drivers::can {

enum class Counter : std::uint8_t {
  kSamples,       // samples delivered to the ring
  kRingDropped,   // samples lost because the consumer was slow
  kGaps,          // missing TPDOs/replies/profiles, counter or sequence gaps
  kCrcErrors,     // profile CRC mismatches
  kTimeouts,      // replies or profile segments that never came
  kFaults,        // EMCY, statusword fault, PowerCube "not ok", ranger overrun
  kBusErrors,     // error frames of any class
  kBusOff,        // controller went bus-off
  kErrorPassive,  // controller reached error-passive
  kRestarts,      // controller restarted after bus-off
  kUnknownIds,    // frames no configured node speaks
  kBadLengths,    // known id, wrong data length
  kDuplicates,    // duplicate SYNC/TPDO/segment
  kReordered,     // SYNC counter or sequence went backwards
  kReboots,       // boot-up heartbeat (node reset)
  kNodesLost,     // heartbeat or replies stopped
  kLinkDowns,     // interface went down
  kReconnects,    // link reopened after going down
  kTxBufferFull,  // our own send found the tx queue full
  kCount,
};

const char* to_string(Counter c);

struct CanCounters {
  std::array<std::uint64_t, static_cast<std::size_t>(Counter::kCount)> values{};
  TransportCounters transport;
  std::uint64_t operator[](Counter c) const { return values[static_cast<std::size_t>(c)]; }
  // The HAL view: drops include kernel receive-queue overflows.
  hal::StreamCounters stream() const;
};

class AtomicCanCounters {
 public:
  void bump(Counter c, std::uint64_t n = 1) {
    values_[static_cast<std::size_t>(c)].fetch_add(n, std::memory_order_relaxed);
  }
  CanCounters snapshot(const TransportCounters& transport) const;

 private:
  std::array<std::atomic<std::uint64_t>, static_cast<std::size_t>(Counter::kCount)> values_{};
};

}  // namespace rangefit::drivers::can
