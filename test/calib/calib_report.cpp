// Spread over many seeds against the reported covariance (what the tests check with few seeds):
//   build/test/calib/calib_report [SEEDS]      (default 20)
// Prints, per parameter, the rms error over the seeds and the mean reported 1 sigma, and their
// ratio (1: the covariance is right).
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "calib/stripe_calibration.hpp"
#include "calib_fixtures.hpp"
#include "sim/calibration_scans.hpp"

using namespace rangefit;
using namespace rangefit::test;

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const hal::StripeCellGeometry nominal;
  const hal::StripeCellGeometry truth = perturbed_cell(nominal, 7);
  const calib::CalibrationCube cube;
  const sim::Scene scene =
      sim::calibration_cube_scene(cube.edge_mm, cube.bar_mm, cube_on_table(), true);
  std::vector<double> axis;
  for (double a = 60.0; a <= 340.0; a += 1.0) axis.push_back(a);
  double err2[6] = {}, sd[6] = {};
  int n = 0;
  for (int s = 0; s < seeds; ++s) {
    const auto profiles = sim::simulate_stripe_sweep(
        scene, truth, axis, {.sigma_mm = 0.06, .seed = 100000u + static_cast<unsigned>(s)});
    calib::StripeCalibrationInput in;
    in.profiles = profiles;
    in.axis_mm = axis;
    in.T_table_cube = cube_on_table();
    const auto r = calib::calibrate_stripe_cell(in, nominal);
    if (!r.ok) {
      std::printf("seed %d: %s\n", s, r.reason.c_str());
      continue;
    }
    const Eigen::Vector3d dp = r.geometry.ranger_position_cell_mm - truth.ranger_position_cell_mm;
    const Eigen::AngleAxisd w(truth.T_cell_ranger().linear().transpose() *
                              r.geometry.T_cell_ranger().linear());
    const Eigen::Vector3d dw = w.angle() * w.axis();
    for (int k = 0; k < 3; ++k) {
      err2[k] += dp[k] * dp[k];
      err2[3 + k] += dw[k] * dw[k];
      sd[k] += r.position_sigma_mm[k];
      sd[3 + k] += r.rotation_sigma_rad[k];
    }
    ++n;
  }
  const char* names[6] = {"x mm", "y mm", "z mm", "rx deg", "ry deg", "rz deg"};
  std::printf("stripe cell, 0.06 mm noise, 1 mm profiles, %d seeds\n", n);
  for (int k = 0; k < 6; ++k) {
    const double scale = k < 3 ? 1.0 : 1.0 / kDeg;
    const double rms = std::sqrt(err2[k] / n) * scale, sigma = sd[k] / n * scale;
    std::printf("  %-7s rms error %.5f  reported sigma %.5f  ratio %.2f\n", names[k], rms, sigma,
                rms / sigma);
  }
  return 0;
}
