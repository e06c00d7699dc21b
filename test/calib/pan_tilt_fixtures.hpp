#pragma once
// The pan-tilt head set-up the calibration tests and calib_report share.

#include <vector>

#include "calib/pan_tilt_calibration.hpp"
#include "calib_fixtures.hpp"
#include "sim/calibration_scans.hpp"

namespace rangefit::test {

// Three pan sweeps over the cube, at tilt -6, 0 and +6 deg, by the true head.
struct PanTiltSweeps {
  std::vector<std::vector<hal::PanTiltSample>> angles;
  std::vector<std::vector<hal::RangerProfile>> profiles;
};

inline PanTiltSweeps pan_tilt_sweeps(const hal::PanTiltGeometry& truth, double sigma_mm,
                                     std::uint64_t seed,
                                     std::vector<double> tilts_deg = {-6.0, 0.0, 6.0},
                                     double step_deg = 0.2, bool quantise = false) {
  const calib::CalibrationCube cube;
  const sim::Scene scene =
      sim::calibration_cube_scene(cube.edge_mm, cube.bar_mm, cube_before_head(), false);
  PanTiltSweeps s;
  for (std::size_t k = 0; k < tilts_deg.size(); ++k) {
    s.angles.push_back(pan_sweep(tilts_deg[k], step_deg));
    s.profiles.push_back(sim::simulate_pan_tilt_sweep(
        scene, truth, s.angles.back(),
        {.sigma_mm = sigma_mm, .quantise = quantise, .seed = seed + k}));
  }
  return s;
}

inline calib::PanTiltCalibrationResult run_pan_tilt(const PanTiltSweeps& s,
                                                    const hal::PanTiltGeometry& start) {
  calib::PanTiltCalibrationInput in;
  for (std::size_t k = 0; k < s.angles.size(); ++k)
    in.sweeps.push_back({s.profiles[k], s.angles[k]});
  in.T_world_cube = cube_before_head();
  return calib::calibrate_pan_tilt(in, start);
}

}  // namespace rangefit::test
