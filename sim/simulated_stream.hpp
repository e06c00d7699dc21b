#pragma once
// Common machinery of the simulated HAL devices: frames are computed lazily, in time order, when
// a consumer reads, and delivered once the clock has passed their due time. With an
// as-fast-as-possible SimClock read() jumps virtual time to the next frame instead of waiting, so
// simulation runs at the speed of the ray casting; with a real-time clock it paces like the
// device. Dropped frames, disconnects and reconnects are reported through health() and show in
// the stream as missing sequence numbers, as a real driver reports them.

#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include "hal/source.hpp"
#include "sim/fault_options.hpp"

namespace rangefit::sim {

// A range the ray caster found no surface for.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Offset of the return ray's ends from the surfaces they touch, mm: well above Embree's float
// rounding at ~300 mm from the origin (~3e-5 mm), well below any feature of a scene.
inline constexpr double kSurfaceEps = 1e-3;

// A duration of s seconds, rounded to the nanosecond.
inline hal::Duration seconds(double s) {
  return hal::Duration(static_cast<std::int64_t>(std::llround(s * 1e9)));
}

// Instant of event k of a periodic schedule: start + k / rate (a device's sampling clock).
inline hal::Timestamp tick(hal::Timestamp start, double rate_hz, std::uint64_t k) {
  return start + seconds(static_cast<double>(k) / rate_hz);
}

// Base is the HAL interface the device implements (a SampleSource<Sample> or a class derived from
// it, such as hal::LinearAxis).
template <class Sample, class Base = hal::SampleSource<Sample>>
class SimulatedStream : public Base {
 public:
  std::string name() const override { return name_; }

  hal::Status start() override {
    std::lock_guard lock(read_mutex_);
    if (streaming_) return hal::Status::Ok();
    // Frames due before start are never delivered (the device was not listening).
    const hal::Timestamp now = clock_.now();
    while (due(next_) < now) ++next_;
    started_at_ = now;
    streaming_ = true;
    set_state(hal::DeviceState::kStreaming, "");
    return hal::Status::Ok();
  }

  void stop() override {
    std::lock_guard lock(read_mutex_);
    streaming_ = false;
    set_state(hal::DeviceState::kReady, "");
  }

  hal::DeviceHealth health() const override {
    std::lock_guard lock(health_mutex_);
    return health_;
  }

  std::size_t read(std::vector<Sample>& out, hal::Duration timeout) override {
    std::lock_guard lock(read_mutex_);
    if (!streaming_) return 0;
    const hal::Timestamp deadline = clock_.now() + timeout;
    std::size_t delivered = 0;
    while (true) {
      const hal::Timestamp now = clock_.now();
      while (due(next_) <= now) delivered += deliver(next_++, out);
      if (delivered > 0) return delivered;
      const hal::Timestamp next = due(next_);
      if (next > deadline) {
        clock_.sleep_until(deadline);
        std::lock_guard h(health_mutex_);
        ++health_.counters.timeouts;
        return 0;
      }
      clock_.sleep_until(next);
    }
  }

 protected:
  SimulatedStream(std::string name, hal::Clock& clock, FaultOptions faults, std::uint64_t seed,
                  std::uint64_t device_id)
      : name_(std::move(name)), clock_(clock), faults_(faults), seed_(seed), device_id_(device_id) {
    health_.state = hal::DeviceState::kReady;
  }

  // Time at which frame k is complete and may be delivered; strictly increasing in k.
  virtual hal::Timestamp due(std::uint64_t k) const = 0;
  // Computes frame k into out; rng is this frame's own generator.
  virtual void make(std::uint64_t k, std::mt19937_64& rng, Sample& out) = 0;

  const FaultOptions& faults() const { return faults_; }
  hal::Clock& clock() const { return clock_; }

  // The stamp a device puts on a frame taken at t: t plus the configured Gaussian jitter.
  hal::Timestamp stamp_at(hal::Timestamp t, std::mt19937_64& rng) const {
    if (faults_.stamp_jitter_sigma.count() <= 0) return t;
    std::normal_distribution<double> n(0.0,
                                       static_cast<double>(faults_.stamp_jitter_sigma.count()));
    return t + hal::Duration(static_cast<std::int64_t>(n(rng)));
  }
  // The reading frame k reports: k itself, or k - 1 when the device repeats its last reading
  // (a stale position or angle, with a fresh stamp).
  std::uint64_t reading_of(std::uint64_t k, std::mt19937_64& rng) const {
    const bool stale = k > 0 && std::bernoulli_distribution(faults_.stale_probability)(rng);
    return stale ? k - 1 : k;
  }

 private:
  bool disconnected_at(hal::Timestamp t) const {
    if (faults_.disconnect_after.count() < 0) return false;
    const hal::Timestamp begin = started_at_ + faults_.disconnect_after;
    return t >= begin && t < begin + faults_.disconnect_for;
  }

  void set_state(hal::DeviceState s, std::string message) {
    std::lock_guard lock(health_mutex_);
    health_.state = s;
    if (!message.empty()) health_.message = std::move(message);
  }

  std::size_t deliver(std::uint64_t k, std::vector<Sample>& out) {
    const hal::Timestamp t = due(k);
    std::mt19937_64 rng = frame_rng(seed_, device_id_, k);
    std::lock_guard lock(health_mutex_);
    if (disconnected_at(t)) {
      if (health_.state != hal::DeviceState::kDisconnected) {
        health_.state = hal::DeviceState::kDisconnected;
        health_.message = name_ + ": link lost (simulated disconnect)";
      }
      ++health_.counters.gaps;
      return 0;
    }
    if (health_.state == hal::DeviceState::kDisconnected) {
      health_.state = hal::DeviceState::kStreaming;
      ++health_.counters.reconnects;
    }
    if (std::bernoulli_distribution(faults_.drop_probability)(rng)) {
      ++health_.counters.gaps;
      health_.message = name_ + ": frame lost (simulated drop)";
      return 0;
    }
    Sample sample;
    make(k, rng, sample);
    out.push_back(std::move(sample));
    ++health_.counters.samples;
    return 1;
  }

  const std::string name_;
  hal::Clock& clock_;
  const FaultOptions faults_;
  const std::uint64_t seed_;
  const std::uint64_t device_id_;
  std::mutex read_mutex_;
  mutable std::mutex health_mutex_;
  hal::DeviceHealth health_;
  bool streaming_ = false;
  std::uint64_t next_ = 0;
  hal::Timestamp started_at_{};
};

// A device polled at a fixed rate whose replies carry a reading of something that moves (joint
// angle, axis position, pan/tilt angles): sample k is taken at tick(start, rate, k), delivered
// reply_delay later, stamped with the configured jitter, and repeats the previous reading when
// stale. fill() writes the reading; the stamp is set here.
template <class Sample, class Base = hal::SampleSource<Sample>>
class PolledStream : public SimulatedStream<Sample, Base> {
 protected:
  PolledStream(std::string name, hal::Clock& clock, FaultOptions faults, std::uint64_t seed,
               std::uint64_t device_id, hal::Timestamp start, double rate_hz,
               hal::Duration reply_delay = hal::Duration(0))
      : SimulatedStream<Sample, Base>(std::move(name), clock, faults, seed, device_id),
        start_(start),
        rate_hz_(rate_hz),
        reply_delay_(reply_delay) {}

  // Instant sample k is taken.
  hal::Timestamp taken(std::uint64_t k) const { return tick(start_, rate_hz_, k); }
  // Writes the reading of sample k taken at t; read_at is the instant whose state it reports.
  virtual void fill(hal::Timestamp t, hal::Timestamp read_at, Sample& out) = 0;

  hal::Timestamp due(std::uint64_t k) const override { return taken(k) + reply_delay_; }
  void make(std::uint64_t k, std::mt19937_64& rng, Sample& out) override {
    const hal::Timestamp read_at = taken(this->reading_of(k, rng));
    out.stamp = this->stamp_at(taken(k), rng);
    fill(taken(k), read_at, out);
  }

 private:
  const hal::Timestamp start_;
  const double rate_hz_;
  const hal::Duration reply_delay_;
};

}  // namespace rangefit::sim
