#pragma once
// The simulator's hal::Clock. With a time scale s > 0 virtual time runs s times as fast as
// CLOCK_MONOTONIC (1 = real time, for demos and hardware-in-the-loop style runs); with s = 0 it
// runs as fast as possible: virtual time stands still until somebody sleeps, and sleep_until(t)
// jumps it to t at once, so a simulated device waiting for its next sample "waits" no time at all.
// Thread-safe; virtual time never goes backwards.

#include <atomic>
#include <cstdint>

#include "hal/time.hpp"

namespace rangefit::sim {

class SimClock final : public hal::Clock {
 public:
  // time_scale: 0 = as fast as possible, otherwise virtual seconds per real second (> 0).
  // start: the virtual time now() returns at construction.
  explicit SimClock(double time_scale = 0.0, hal::Timestamp start = std::chrono::seconds(1000));

  hal::Timestamp now() const override;
  void sleep_until(hal::Timestamp t) override;

  bool as_fast_as_possible() const { return time_scale_ <= 0.0; }
  double time_scale() const { return time_scale_; }

 private:
  const double time_scale_;
  const hal::Timestamp start_virtual_;
  const hal::Timestamp start_real_;
  std::atomic<std::int64_t> virtual_ns_;  // as-fast-as-possible mode only
};

}  // namespace rangefit::sim
