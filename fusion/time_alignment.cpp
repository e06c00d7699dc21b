#include "fusion/time_alignment.hpp"

#include <algorithm>
#include <string>

namespace rangefit::fusion {

bool FrameCheck::accept(std::uint32_t sequence, hal::Timestamp stamp, hal::Duration expected_period,
                        const TimeLimits& limits, TimeFaults& faults) {
  if (!has_last_) {
    has_last_ = true;
    last_sequence_ = sequence;
    last_stamp_ = stamp;
    last_step_ = expected_period;
    return true;
  }
  // Unsigned difference, so a counter wrap counts as a step forward.
  const std::uint32_t step = sequence - last_sequence_;
  const hal::Duration dt = stamp - last_stamp_;
  if (step == 0 || step > 0x7fffffffu || dt <= hal::Duration::zero()) {
    ++faults.out_of_order;
    return false;
  }
  if (step > 1) ++faults.gaps;  // lost frames
  const hal::Duration period =
      expected_period > hal::Duration::zero() ? expected_period : last_step_;
  if (period > hal::Duration::zero()) {
    const hal::Duration expected = period * static_cast<std::int64_t>(step);
    const hal::Duration deviation = dt > expected ? dt - expected : expected - dt;
    if (deviation > limits.clock_jump_tolerance) ++faults.clock_jumps;
  }
  last_step_ = dt / static_cast<std::int64_t>(step);
  last_sequence_ = sequence;
  last_stamp_ = stamp;
  return true;
}

void ReferenceTrack::push(const Sample& s, const TimeLimits& limits, TimeFaults& faults) {
  if (!samples_.empty()) {
    const hal::Duration dt = s.stamp - samples_.back().stamp;
    if (dt <= hal::Duration::zero()) {
      ++faults.out_of_order;
      return;
    }
    if (dt > limits.max_reference_gap) ++faults.gaps;
  }
  samples_.push_back(s);
}

std::size_t ReferenceTrack::locate(hal::Timestamp t) const {
  if (samples_.size() < 2) return 0;
  const auto it = std::upper_bound(samples_.begin(), samples_.end(), t,
                                   [](hal::Timestamp v, const Sample& s) { return v < s.stamp; });
  const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - samples_.begin() - 1, 0));
  return std::min(k, samples_.size() - 2);
}

void apply_fault_limit(const TimeLimits& limits, FusedScan& scan) {
  const TimeFaults& f = scan.faults;
  scan.bad = f.total() > limits.max_faults;
  if (!scan.bad) {
    scan.reason.clear();
    return;
  }
  scan.reason = std::to_string(f.total()) + " time-alignment faults exceed the limit of " +
                std::to_string(limits.max_faults) + " (out of order " +
                std::to_string(f.out_of_order) + ", gaps " + std::to_string(f.gaps) +
                ", extrapolated " + std::to_string(f.extrapolated) + ", clock jumps " +
                std::to_string(f.clock_jumps) + ")";
}

}  // namespace rangefit::fusion
