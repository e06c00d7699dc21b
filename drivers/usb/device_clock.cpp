#include "drivers/usb/device_clock.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit::drivers::css_usb {

std::int64_t DeviceClock::unwrap(std::uint64_t raw) {
  if (!have_raw_) {
    have_raw_ = true;
    last_raw_ = raw;
    last_unwrapped_ = static_cast<std::int64_t>(raw);
    return last_unwrapped_;
  }
  std::int64_t delta = 0;
  if (options_.counter_bits >= 64) {
    delta = static_cast<std::int64_t>(raw - last_raw_);
  } else {
    const std::uint64_t span = std::uint64_t{1} << options_.counter_bits;
    const std::uint64_t forward = (raw - last_raw_) & (span - 1);
    // Values may arrive slightly out of order (stamps vs exchanges): half the range each way.
    delta = forward >= span / 2
                ? static_cast<std::int64_t>(forward) - static_cast<std::int64_t>(span)
                : static_cast<std::int64_t>(forward);
  }
  last_raw_ = raw;
  last_unwrapped_ += delta;
  return last_unwrapped_;
}

bool DeviceClock::add_exchange(hal::Timestamp host_before, std::uint64_t device_us,
                               hal::Timestamp host_after) {
  const hal::Duration round_trip = host_after - host_before;
  if (round_trip < hal::Duration::zero() || round_trip > options_.max_round_trip) return false;
  const std::int64_t device = unwrap(device_us);
  const hal::Timestamp midpoint = host_before + round_trip / 2;
  if (samples_.empty()) {
    origin_device_us_ = device;
    origin_host_ = midpoint;
  }
  samples_.push_back({static_cast<double>(device - origin_device_us_),
                      static_cast<double>((midpoint - origin_host_).count()),
                      static_cast<double>(round_trip.count()) / 1e3});
  while (samples_.size() > options_.window) samples_.pop_front();
  fit();
  return true;
}

void DeviceClock::fit() {
  double fastest_us = samples_.front().round_trip_us;
  for (const Sample& s : samples_) fastest_us = std::min(fastest_us, s.round_trip_us);
  // Error bound of an exchange's midpoint relative to the fastest one, plus the counter's 1 us.
  auto weight = [&](const Sample& s) {
    const double bound_us = 1.0 + (s.round_trip_us - fastest_us) / 2.0;
    return 1.0 / (bound_us * bound_us);
  };
  double sw = 0, sx = 0, sy = 0;
  for (const Sample& s : samples_) {
    sw += weight(s);
    sx += weight(s) * s.device_us;
    sy += weight(s) * s.host_ns;
  }
  const double mx = sx / sw;
  const double my = sy / sw;
  double sxx = 0, sxy = 0;
  for (const Sample& s : samples_) {
    sxx += weight(s) * (s.device_us - mx) * (s.device_us - mx);
    sxy += weight(s) * (s.device_us - mx) * (s.host_ns - my);
  }
  const double span_us = samples_.back().device_us - samples_.front().device_us;
  double slope = 1000.0;
  if (span_us * 1e3 >= static_cast<double>(options_.min_fit_span.count()) && sxx > 0.0) {
    slope = sxy / sxx;
    // Standard error of the weighted slope from the residuals (ns/us -> ppm: x 1000).
    double srr = 0.0;
    for (const Sample& s : samples_) {
      const double r = s.host_ns - my - slope * (s.device_us - mx);
      srr += weight(s) * r * r;
    }
    const double n = static_cast<double>(samples_.size());
    const double error_ppm = n > 2.0 ? std::sqrt(srr / (n - 2.0) / sxx) * 1e3 : 1e9;
    if (!std::isfinite(slope) || std::abs(slope / 1000.0 - 1.0) * 1e6 > options_.max_drift_ppm ||
        !(error_ppm <= options_.max_slope_error_ppm)) {
      slope = 1000.0;
    }
  }
  slope_ns_per_us_ = slope;
  intercept_ns_ = my - slope * mx;
}

std::optional<hal::Timestamp> DeviceClock::to_host(std::uint64_t device_us) {
  if (samples_.empty()) return std::nullopt;
  const double x = static_cast<double>(unwrap(device_us) - origin_device_us_);
  const double host_ns = intercept_ns_ + slope_ns_per_us_ * x;
  return origin_host_ + hal::Duration(static_cast<std::int64_t>(std::llround(host_ns)));
}

hal::Duration DeviceClock::duration_to_host(std::uint32_t device_us) const {
  return hal::Duration(std::llround(slope_ns_per_us_ * static_cast<double>(device_us)));
}

void DeviceClock::reset() {
  samples_.clear();
  have_raw_ = false;
  intercept_ns_ = 0.0;
  slope_ns_per_us_ = 1000.0;
}

}  // namespace rangefit::drivers::css_usb
