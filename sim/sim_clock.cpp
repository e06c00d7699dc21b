#include "sim/sim_clock.hpp"

#include <cmath>

namespace rangefit::sim {

SimClock::SimClock(double time_scale, hal::Timestamp start)
    : time_scale_(std::isfinite(time_scale) && time_scale > 0.0 ? time_scale : 0.0),
      start_virtual_(start),
      start_real_(hal::monotonic_now()),
      virtual_ns_(start.count()) {}

hal::Timestamp SimClock::now() const {
  if (as_fast_as_possible()) return hal::Timestamp(virtual_ns_.load());
  const double real_ns = static_cast<double>((hal::monotonic_now() - start_real_).count());
  return start_virtual_ + hal::Duration(static_cast<std::int64_t>(real_ns * time_scale_));
}

void SimClock::sleep_until(hal::Timestamp t) {
  if (as_fast_as_possible()) {
    // Jump to t unless another thread already moved time past it.
    std::int64_t current = virtual_ns_.load();
    while (current < t.count() && !virtual_ns_.compare_exchange_weak(current, t.count())) {
    }
    return;
  }
  const double virtual_ns = static_cast<double>((t - start_virtual_).count());
  const auto real_target =
      start_real_ + hal::Duration(static_cast<std::int64_t>(virtual_ns / time_scale_));
  hal::MonotonicClock().sleep_until(real_target);
}

}  // namespace rangefit::sim
