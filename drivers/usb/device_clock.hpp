#pragma once
// Device clock -> host CLOCK_MONOTONIC translation for the CSS (thesis 4.2.1 stamps revolutions
// with 1 us resolution). Two-way exchanges: the host stamps just before a GET_TIME request and just
// after its reply; the device counter was read somewhere in between, best estimated at the
// midpoint, with an error bounded by half of the round trip's excess over the fastest one seen
// (the part of the latency that may be asymmetric). A weighted least-squares line through the
// recent exchanges (weight 1/(1 us + excess/2)^2, so the fastest exchanges dominate) gives offset
// and drift; the device counter may be narrower than 64 bits and is unwrapped. Pure: no I/O.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

#include "hal/time.hpp"

namespace rangefit::drivers::css_usb {

struct ClockOptions {
  int counter_bits = 64;    // device us counter wraps at 2^counter_bits
  std::size_t window = 64;  // exchanges kept for the fit
  hal::Duration max_round_trip = std::chrono::milliseconds(5);  // slower exchanges are discarded
  double max_drift_ppm = 1000.0;  // fitted drift beyond this falls back to nominal rate
  // Drift needs a time base: over USB (measured on dummy_hcd in the HIL VM) the reading sits
  // 30-130 us off the exchange midpoint, which over 0.5 s would fake ~500 ppm.
  hal::Duration min_fit_span = std::chrono::seconds(5);
  double max_slope_error_ppm = 20.0;  // fitted drift with a larger standard error: nominal rate
};

class DeviceClock {
 public:
  explicit DeviceClock(ClockOptions options = {}) : options_(options) {}

  // One GET_TIME exchange. Returns false when rejected (round trip negative or too long).
  bool add_exchange(hal::Timestamp host_before, std::uint64_t device_us, hal::Timestamp host_after);

  // Host time of a device counter value; nullopt until the first exchange.
  std::optional<hal::Timestamp> to_host(std::uint64_t device_us);
  // A device duration in host time (drift-corrected).
  hal::Duration duration_to_host(std::uint32_t device_us) const;

  bool synchronised() const { return !samples_.empty(); }
  // How fast the device counter runs relative to the host clock, ppm (+50 = 50 us/s fast).
  double drift_ppm() const { return (1000.0 / slope_ns_per_us_ - 1.0) * 1e6; }
  std::size_t exchanges() const { return samples_.size(); }

  // Forgets everything (device replugged: its counter restarted).
  void reset();

 private:
  struct Sample {
    double device_us;  // unwrapped, relative to origin_device_us_
    double host_ns;    // exchange midpoint, relative to origin_host_
    double round_trip_us;
  };

  std::int64_t unwrap(std::uint64_t raw);
  void fit();

  ClockOptions options_;
  std::deque<Sample> samples_;
  bool have_raw_ = false;
  std::uint64_t last_raw_ = 0;
  std::int64_t last_unwrapped_ = 0;
  std::int64_t origin_device_us_ = 0;
  hal::Timestamp origin_host_{};
  double intercept_ns_ = 0.0;        // host_ns at device_us = 0 (relative origins)
  double slope_ns_per_us_ = 1000.0;  // host ns per device us
};

}  // namespace rangefit::drivers::css_usb
