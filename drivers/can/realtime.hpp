#pragma once
// Optional real-time settings for a driver thread. Nothing here runs unless configured, and it
// runs on the driver's own thread at start, never hidden in a constructor.

#include "hal/device.hpp"

namespace rangefit::drivers::can {

struct RealtimeConfig {
  bool fifo = false;         // SCHED_FIFO for the receive thread (needs CAP_SYS_NICE)
  int priority = 50;         // 1..99
  bool lock_memory = false;  // mlockall(MCL_CURRENT | MCL_FUTURE): process-wide, opt-in
};

// Applies cfg to the calling thread; an error says which part failed (the thread keeps running).
hal::Status apply_realtime(const RealtimeConfig& cfg);

}  // namespace rangefit::drivers::can
