#include "test/hil/cell_peer/css_sweep.hpp"

#include <cmath>

#include "test/hil/cell_peer/sweep_timeline.hpp"

namespace rangefit::hil {

CssSweep::CssSweep(const RevolutionSource& forward, CssSweepOptions options, hal::Timestamp origin)
    : forward_(forward), options_(options), origin_(origin) {
  // Whole revolutions per cycle, so revolution j of every cycle sees the same sweep phase.
  const double cycle =
      options_.scan_s + options_.end_dwell_s + options_.return_s + options_.dwell_s;
  cycle_revolutions_ = static_cast<std::uint64_t>(std::ceil(cycle / options_.period_s));
}

double CssSweep::omega_at(hal::Timestamp t) const {
  // Eq. 4.21: omega = -delta + v t / R, with v chosen so that 2 delta R takes scan_s.
  const SweepTimeline line{.half_rad = options_.deflection_rad,
                           .forward_s = options_.scan_s,
                           .end_dwell_s = options_.end_dwell_s,
                           .return_s = options_.return_s,
                           .dwell_s = options_.dwell_s};
  return line.angle_at(static_cast<double>((t - origin_).count()) * 1e-9, cycle_s());
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
