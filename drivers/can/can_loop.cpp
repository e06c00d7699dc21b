#include "drivers/can/can_loop.hpp"

#include <linux/can/error.h>

#include <algorithm>
#include <array>

namespace rangefit::drivers::can {

const char* to_string(Problem p) {
  switch (p) {
    case Problem::kNone:
      return "";
    case Problem::kLinkDown:
      return "interface down";
    case Problem::kBusOff:
      return "bus-off";
    case Problem::kErrorPassive:
      return "controller error-passive";
    case Problem::kNodeLost:
      return "node silent (heartbeat or replies lost)";
    case Problem::kNodeReboot:
      return "node rebooted";
    case Problem::kEmcy:
      return "EMCY received";
    case Problem::kDeviceFault:
      return "device reports a fault";
    case Problem::kCrcError:
      return "CRC error";
    case Problem::kTimeout:
      return "reply timeout";
    case Problem::kRealtime:
      return "real-time settings could not be applied";
  }
  return "?";
}

CanLoop::CanLoop(CanTransport& transport, CanLoopHandler& handler, AtomicCanCounters& counters,
                 LoopConfig config)
    : transport_(transport), handler_(handler), counters_(counters), config_(config) {}

void CanLoop::start(bool link_up) {
  if (thread_.joinable()) return;
  stop_ = false;
  link_up_ = link_up;
  thread_ = std::thread([this] { run(); });
}

void CanLoop::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void CanLoop::handle_error_frame(const CanFrame& f) {
  counters_.bump(Counter::kBusErrors);
  if (f.id & CAN_ERR_BUSOFF) {
    counters_.bump(Counter::kBusOff);
    bus_off_ = true;
  }
  if (f.id & CAN_ERR_RESTARTED) {
    counters_.bump(Counter::kRestarts);
    bus_off_ = false;
  }
  if ((f.id & CAN_ERR_CRTL) && f.len > 1 &&
      (f.data[1] & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE))) {
    counters_.bump(Counter::kErrorPassive);
  }
}

void CanLoop::run() {
  if (config_.realtime.fifo || config_.realtime.lock_memory) {
    realtime_failed_ = !apply_realtime(config_.realtime).ok;
  }
  std::array<CanFrame, 64> frames{};
  hal::Duration backoff = config_.backoff_min;
  hal::Timestamp next_tick = handler_.on_tick(hal::monotonic_now());
  int drained = 0;  // full batches taken while a tick was due
  while (!stop_.load(std::memory_order_relaxed)) {
    if (!link_up_.load(std::memory_order_relaxed)) {
      // Sleep in short slices so stop() stays prompt during long back-offs.
      const hal::Timestamp until = hal::monotonic_now() + backoff;
      while (!stop_ && hal::monotonic_now() < until) {
        std::this_thread::sleep_for(
            std::min<hal::Duration>(until - hal::monotonic_now(), std::chrono::milliseconds(10)));
      }
      if (stop_) break;
      if (transport_.reopen().ok) {
        link_up_ = true;
        bus_off_ = false;
        backoff = config_.backoff_min;
        counters_.bump(Counter::kReconnects);
        handler_.on_link(true);
        next_tick = handler_.on_tick(hal::monotonic_now());
      } else {
        backoff = std::min(backoff * 2, config_.backoff_max);
      }
      continue;
    }
    // A due tick first takes what is already queued, so a thread that was not scheduled for a
    // while does not time out a profile or a reply whose frames wait in the socket; under a
    // flood it runs after at most kMaxDrain full batches anyway.
    constexpr int kMaxDrain = 4;
    const hal::Timestamp now = hal::monotonic_now();
    const bool tick_due = now >= next_tick;
    // Wake at least every 50 ms so stop() is honoured on a silent bus.
    const hal::Duration wait = tick_due
                                   ? hal::Duration{0}
                                   : std::clamp<hal::Duration>(next_tick - now, hal::Duration{0},
                                                               std::chrono::milliseconds(50));
    const RxResult r = transport_.receive(frames, wait);
    if (r.link_down) {
      link_up_ = false;
      counters_.bump(Counter::kLinkDowns);
      handler_.on_link(false);
      continue;
    }
    for (std::size_t i = 0; i < r.frames; ++i) {
      if (frames[i].flags & kFrameError) {
        handle_error_frame(frames[i]);
      } else {
        handler_.on_frame(frames[i]);
      }
    }
    drained = tick_due ? drained + 1 : 0;
    if (tick_due && (r.frames < frames.size() || drained >= kMaxDrain)) {
      next_tick = handler_.on_tick(hal::monotonic_now());
      drained = 0;
    }
    handler_.on_batch_end();
  }
}

}  // namespace rangefit::drivers::can
