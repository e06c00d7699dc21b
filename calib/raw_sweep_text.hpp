#pragma once
// The raw sweeps the calibrations read, as text (what `rangefit calibrate --scans` takes): the
// ranger's profiles before any extrinsic is applied, each with the axis position or the pan/tilt
// angles it was taken at. One sample per line, '#' starts a comment:
//
//   rangefit-raw-sweep 1 stripe 512      # or: pantilt; then the points per profile
//   p 152.5                              # a profile at axis position 152.5 mm
//   17 -41.25 402.125                    # point k = 17: ranger x_mm, z_mm
//   p 0.12 -0.05                         # pantilt: a profile at pan, tilt (rad, as reported)
//
// Parsing and formatting are pure (text in, value or reason out); the command reads the file.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hal/samples.hpp"

namespace rangefit::calib {

enum class SweepKind { kStripe, kPanTilt };

struct RawSweep {
  SweepKind kind = SweepKind::kStripe;
  int points_per_profile = 512;
  std::vector<double> axis_mm;             // stripe: one per profile
  std::vector<hal::PanTiltSample> angles;  // pantilt: one per profile
  std::vector<hal::RangerProfile> profiles;
};

struct RawSweepParse {
  std::optional<RawSweep> sweep;
  std::string error;  // "<source>:<line>: <problem>" when not
};

RawSweepParse parse_raw_sweep(std::string_view text, std::string_view source = "sweep");
std::string format_raw_sweep(const RawSweep& sweep);

}  // namespace rangefit::calib
