#pragma once
// The time-alignment pieces all assemblers share: the fault limits, a check of the frame
// stream's sequence and stamps, and the reference track that interpolates joint angles, axis
// positions or pan/tilt angles at any instant. Nothing here smooths: every irregularity is
// counted in TimeFaults (fusion/fused_scan.hpp).

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
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

  // Index of the segment to start from for instants at or after t.
  std::size_t locate(hal::Timestamp t) const;
  // Evaluates channel 0 and 1 at increasing offsets from one base instant, keeping the current
  // segment's line, so each evaluation is a compare and a multiply-add. Requires !empty().
  class Cursor {
   public:
    Cursor(const ReferenceTrack& track, hal::Timestamp base)
        : track_(track),
          base_(base),
          n_(track.samples_.size()),
          first_(track.rel(0, base)),
          last_(track.rel(n_ - 1, base)),
          segment_(track.locate(base)) {
      load();
    }
    Value at(double offset_ns) {
      while (offset_ns >= next_ && segment_ + 2 < n_) {
        ++segment_;
        load();
      }
      const double dt = offset_ns - t_a_;
      return {v0_ + dt * slope0_, v1_ + dt * slope1_, offset_ns < first_ || offset_ns > last_};
    }

   private:
    void load() {
      const Sample& a = track_.samples_[segment_];
      t_a_ = track_.rel(segment_, base_);
      v0_ = a.v0;
      v1_ = a.v1;
      if (segment_ + 1 < n_) {
        const Sample& b = track_.samples_[segment_ + 1];
        const double span = static_cast<double>((b.stamp - a.stamp).count());
        slope0_ = (b.v0 - a.v0) / span;
        slope1_ = (b.v1 - a.v1) / span;
        next_ = t_a_ + span;
      } else {  // a single sample: hold it
        slope0_ = slope1_ = 0.0;
        next_ = std::numeric_limits<double>::infinity();
      }
    }
    const ReferenceTrack& track_;
    hal::Timestamp base_;
    std::size_t n_;
    double first_, last_;  // offsets of the first and last sample
    std::size_t segment_;
    double t_a_ = 0.0, next_ = 0.0, v0_ = 0.0, v1_ = 0.0, slope0_ = 0.0, slope1_ = 0.0;
  };

 private:
  double rel(std::size_t k, hal::Timestamp base) const {
    return static_cast<double>((samples_[k].stamp - base).count());
  }
  std::vector<Sample> samples_;
};

// Marks the scan bad when its faults exceed the limit, with a reason naming the counts.
void apply_fault_limit(const TimeLimits& limits, FusedScan& scan);

}  // namespace rangefit::fusion
