#pragma once
// The time-alignment pieces all assemblers share: the fault limits, a check of the frame
// stream's sequence and stamps, and the reference track that interpolates joint angles, axis
// positions or pan/tilt angles at any instant. Nothing here smooths: every irregularity is
// counted in TimeFaults (fusion/fused_scan.hpp).

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fusion/fused_scan.hpp"
#include "hal/time.hpp"

namespace rangefit::fusion {

struct TimeLimits {
  // Reference samples further apart than this are a gap. The CSS robot joint and the axis are
  // polled at >= 100 Hz, so 50 ms means several samples lost in a row.
  hal::Duration max_reference_gap = std::chrono::milliseconds(50);
  // A frame stamp step that differs from the expected one (device period times the sequence
  // step) by more than this is a clock jump. Host stamping jitter is well below 1 ms.
  hal::Duration clock_jump_tolerance = std::chrono::milliseconds(2);
  // Frames wait at most this many for the reference stream to catch up; the oldest is then fused
  // with an extrapolated pose (and counted).
  std::size_t max_pending_frames = 4;
  // A scan with more faults than this in total is marked bad.
  std::uint32_t max_faults = 10;
};

// Sequence and stamp check of the frame stream (revolutions or profiles).
class FrameCheck {
 public:
  void reset() { has_last_ = false; }
  // Classifies a frame against the last accepted one and counts its faults. Returns false when
  // the frame is out of order and must be dropped. expected_period is the device's frame period
  // (zero: use the step between the last two accepted frames; no check until there is one).
  bool accept(std::uint32_t sequence, hal::Timestamp stamp, hal::Duration expected_period,
              const TimeLimits& limits, TimeFaults& faults);

 private:
  bool has_last_ = false;
  std::uint32_t last_sequence_ = 0;
  hal::Timestamp last_stamp_{};
  hal::Duration last_step_{};  // stamp step per sequence step of the last accepted pair
};

// Time series of a reference quantity with up to two channels (joint angle; axis position;
// pan and tilt), linearly interpolated between samples and linearly extrapolated past either end.
class ReferenceTrack {
 public:
  struct Sample {
    hal::Timestamp stamp{};
    double v0 = 0.0;
    double v1 = 0.0;
  };
  struct Value {
    double v0 = 0.0;
    double v1 = 0.0;
    bool extrapolated = false;  // the instant lies before the first or after the last sample
  };

  void clear() { samples_.clear(); }
  void reserve(std::size_t n) { samples_.reserve(n); }
  // Appends a sample; an out-of-order one is dropped and counted, a gap is counted.
  void push(const Sample& s, const TimeLimits& limits, TimeFaults& faults);

  bool empty() const { return samples_.empty(); }
  std::size_t size() const { return samples_.size(); }
  hal::Timestamp last_stamp() const { return samples_.back().stamp; }

  // Index of the segment to start from for instants at or after t (for at()).
  std::size_t locate(hal::Timestamp t) const;
  // Value at base + offset_ns. `segment` (from locate(base)) is advanced, so a run of increasing
  // offsets costs O(1) each. Requires !empty().
  Value at(hal::Timestamp base, double offset_ns, std::size_t& segment) const {
    const std::size_t n = samples_.size();
    if (n == 1) {
      return {samples_[0].v0, samples_[0].v1, offset_ns != rel(0, base)};
    }
    while (segment + 2 < n && rel(segment + 1, base) <= offset_ns) ++segment;
    const Sample& a = samples_[segment];
    const Sample& b = samples_[segment + 1];
    const double ta = rel(segment, base);
    const double f = (offset_ns - ta) / static_cast<double>((b.stamp - a.stamp).count());
    const bool outside = offset_ns < rel(0, base) || offset_ns > rel(n - 1, base);
    return {a.v0 + f * (b.v0 - a.v0), a.v1 + f * (b.v1 - a.v1), outside};
  }

 private:
  double rel(std::size_t k, hal::Timestamp base) const {
    return static_cast<double>((samples_[k].stamp - base).count());
  }
  std::vector<Sample> samples_;
};

// Marks the scan bad when its faults exceed the limit, with a reason naming the counts.
void apply_fault_limit(const TimeLimits& limits, FusedScan& scan);

}  // namespace rangefit::fusion
