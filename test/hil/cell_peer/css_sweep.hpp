#pragma once
// The robot program of the CSS cell, as the cell peer plays it: the last joint pivots the sensor
// from -delta to +delta at the TCP speed of eq. 4.21 (the forward stroke the service records),
// stops, returns to -delta with the laser off, dwells, and starts again, for ever. One timeline
// drives both device peers: the joint's angle at any instant (answered to every SYNC) and the
// revolution the sensor measured at index pulse j (cast by the simulated cell, sim::CssRig, for the
// forward stroke; no returns on the way back). Pure: no I/O after construction, no threads.

#include <array>
#include <cstdint>
#include <string>

#include "hal/time.hpp"
#include "test/hil/css_gadget/device_model.hpp"

namespace rangefit::hil {

struct CssSweepOptions {
  double deflection_rad = 5.0 * 3.14159265358979323846 / 180.0;  // delta, as fusion.css
  double pivot_radius_mm = 285.8;                                // R, as hal::CssGeometry
  double scan_s = 6.0;          // forward stroke duration (thesis: 25 s)
  double end_dwell_s = 0.3;     // at +delta, laser off (the robot stops before it returns)
  double return_s = 1.0;        // back to -delta, laser off
  double dwell_s = 0.5;         // at -delta before the next stroke
  double period_s = 1.0 / 7.0;  // revolution period (the sensor's 7 Hz)
};

class CssSweep {
 public:
  // forward: the forward stroke's revolutions (RevolutionSource of the same scan_s).
  CssSweep(const RevolutionSource& forward, CssSweepOptions options, hal::Timestamp origin);

  // Path angle omega (rad) at host time t; -delta before the origin.
  double omega_at(hal::Timestamp t) const;
  // Revolution j since the origin: the forward stroke's samples, or false (laser off).
  bool revolution(std::uint64_t j,
                  std::array<drivers::css_usb::WireSample, drivers::css_usb::kSamples>& out) const;
  hal::Timestamp origin() const { return origin_; }
  double cycle_s() const { return static_cast<double>(cycle_revolutions_) * options_.period_s; }

 private:
  const RevolutionSource& forward_;
  CssSweepOptions options_;
  hal::Timestamp origin_;
  std::uint64_t cycle_revolutions_ = 0;
};

}  // namespace rangefit::hil
