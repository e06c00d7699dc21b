#pragma once
// The receive thread every CAN driver runs: waits for frames until the driver's next periodic
// deadline, hands frames to the driver's codec logic, decodes error frames (bus-off, error
// passive, restart) and reopens a downed interface with exponential back-off. The loop itself
// neither allocates nor locks nor logs after start.

#include <atomic>
#include <cstdint>
#include <thread>

#include "drivers/can/can_counters.hpp"
#include "drivers/can/realtime.hpp"
#include "drivers/can/transport.hpp"

namespace rangefit::drivers::can {

// What a driver reports as its last problem (health().message); kept as an enum so the receive
// path never formats strings.
enum class Problem : std::uint8_t {
  kNone,
  kLinkDown,
  kBusOff,
  kErrorPassive,
  kNodeLost,
  kNodeReboot,
  kEmcy,
  kDeviceFault,
  kCrcError,
  kTimeout,
  kRealtime,
};
const char* to_string(Problem p);

class CanLoopHandler {
 public:
  virtual ~CanLoopHandler() = default;
  // Periodic work (SYNC, polls, expiry); returns the time it wants to run next.
  virtual hal::Timestamp on_tick(hal::Timestamp now) = 0;
  virtual void on_frame(const CanFrame& frame) = 0;
  // The link went down (false) or was reopened (true).
  virtual void on_link(bool up) = 0;
  // After each received batch and each tick: publish what the frames produced.
  virtual void on_batch_end() {}
};

struct LoopConfig {
  RealtimeConfig realtime;
  hal::Duration backoff_min = std::chrono::milliseconds(20);
  hal::Duration backoff_max = std::chrono::seconds(2);
};

class CanLoop {
 public:
  CanLoop(CanTransport& transport, CanLoopHandler& handler, AtomicCanCounters& counters,
          LoopConfig config);
  ~CanLoop() { stop(); }
  CanLoop(const CanLoop&) = delete;
  CanLoop& operator=(const CanLoop&) = delete;

  // link_up = false when the first open failed: the loop then retries with back-off.
  void start(bool link_up);
  void stop();
  bool link_up() const { return link_up_.load(); }
  bool bus_off() const { return bus_off_.load(); }
  Problem realtime_problem() const {
    return realtime_failed_.load() ? Problem::kRealtime : Problem::kNone;
  }

 private:
  void run();
  void handle_error_frame(const CanFrame& f);

  CanTransport& transport_;
  CanLoopHandler& handler_;
  AtomicCanCounters& counters_;
  LoopConfig config_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> link_up_{true};
  std::atomic<bool> bus_off_{false};
  std::atomic<bool> realtime_failed_{false};
};

}  // namespace rangefit::drivers::can
