#pragma once
// What every device (real driver or simulated) reports about itself: a state, counters of what
// went wrong, and a status for calls that can fail. Cyclic paths return Status; they never throw.

#include <atomic>
#include <cstdint>
#include <string>
#include <utility>

namespace rangefit::hal {

struct [[nodiscard]] Status {
  bool ok = true;
  std::string message;  // empty when ok

  static Status Ok() { return {}; }
  static Status Error(std::string msg) { return {false, std::move(msg)}; }
  explicit operator bool() const { return ok; }
};

enum class DeviceState : std::uint8_t {
  kDisconnected,  // not present or link down; the device retries by itself
  kConnecting,    // present, being opened or configured
  kReady,         // configured, not streaming
  kStreaming,     // delivering samples
  kFault,         // the device reports a fault; commands are refused until reset
};

const char* to_string(DeviceState s);

// Counters only ever increase. Drivers bump them from their receive path (atomics, no locks).
struct StreamCounters {
  std::uint64_t samples = 0;      // samples delivered
  std::uint64_t dropped = 0;      // lost because a bounded buffer was full
  std::uint64_t gaps = 0;         // sequence numbers or periods missing on the wire
  std::uint64_t crc_errors = 0;   // corrupt frames or transfers
  std::uint64_t resyncs = 0;      // parser had to search for the next frame start
  std::uint64_t timeouts = 0;     // expected data did not arrive in time
  std::uint64_t faults = 0;       // device-reported faults (EMCY, FAULT bit, flags)
  std::uint64_t reconnects = 0;   // link lost and re-established
};

struct DeviceHealth {
  DeviceState state = DeviceState::kDisconnected;
  StreamCounters counters;
  std::string message;  // last problem, human readable; empty when none
  // The device's own identity (its serial number) once it has told it; empty until then or when
  // the protocol has none. Diagnostics report it as hardware_id, else the configured name.
  std::string hardware_id;
};

// Base of every HAL device. start() and stop() are idempotent; health() is cheap and thread-safe.
class Device {
 public:
  virtual ~Device() = default;
  virtual std::string name() const = 0;
  virtual Status start() = 0;
  virtual void stop() = 0;
  virtual DeviceHealth health() const = 0;
};

}  // namespace rangefit::hal
