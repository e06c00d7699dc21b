#include "test/hil/cell_peer/css_sweep.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit::hil {

CssSweep::CssSweep(const RevolutionSource& forward, CssSweepOptions options, hal::Timestamp origin)
    : forward_(forward), options_(options), origin_(origin) {
  // Whole revolutions per cycle, so revolution j of every cycle sees the same sweep phase.
  const double cycle =
      options_.scan_s + options_.end_dwell_s + options_.return_s + options_.dwell_s;
  cycle_revolutions_ = static_cast<std::uint64_t>(std::ceil(cycle / options_.period_s));
}

double CssSweep::omega_at(hal::Timestamp t) const {
  const double delta = options_.deflection_rad;
  const double since = static_cast<double>((t - origin_).count()) * 1e-9;
  if (since < 0.0) return -delta;
  const double tau = std::fmod(since, cycle_s());
  if (tau < options_.scan_s) {
    // Eq. 4.21: omega = -delta + v t / R, with v chosen so that 2 delta R takes scan_s.
    return std::min(delta, -delta + 2.0 * delta * tau / options_.scan_s);
  }
  // The robot stops at +delta (so that every SYNC master sees the end), then returns.
  const double back = tau - options_.scan_s - options_.end_dwell_s;
  if (back < 0.0) return delta;
  if (back < options_.return_s) return delta - 2.0 * delta * back / options_.return_s;
  return -delta;
}

bool CssSweep::revolution(
    std::uint64_t j,
    std::array<drivers::css_usb::WireSample, drivers::css_usb::kSamples>& out) const {
  const std::uint64_t k = j % cycle_revolutions_;
  if (k < forward_.size()) {
    out = forward_.samples(k);
    return true;
  }
  out.fill({drivers::css_usb::kNoReturn, 0, 0});
  return false;
}

}  // namespace rangefit::hil
