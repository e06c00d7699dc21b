#pragma once
// Time in rangefit: std::chrono nanoseconds of CLOCK_MONOTONIC, everywhere. Device clocks are
// translated to this base by their driver before a sample leaves it.

#include <chrono>
#include <ctime>

namespace rangefit::hal {

using Timestamp = std::chrono::nanoseconds;  // since CLOCK_MONOTONIC's epoch (boot)
using Duration = std::chrono::nanoseconds;

// The clock that drivers, the simulator and fusion share. The real one reads CLOCK_MONOTONIC;
// the simulator's can run faster than real time (sim/), so nothing may call the OS clock directly.
class Clock {
 public:
  virtual ~Clock() = default;
  virtual Timestamp now() const = 0;
  virtual void sleep_until(Timestamp t) = 0;
};

inline Timestamp monotonic_now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec);
}

class MonotonicClock final : public Clock {
 public:
  Timestamp now() const override { return monotonic_now(); }
  void sleep_until(Timestamp t) override {
    timespec ts{};
    ts.tv_sec = static_cast<time_t>(std::chrono::duration_cast<std::chrono::seconds>(t).count());
    ts.tv_nsec = static_cast<long>((t - std::chrono::seconds(ts.tv_sec)).count());
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
    }
  }
};

}  // namespace rangefit::hal
