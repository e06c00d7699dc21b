#pragma once
// The CSS hand-eye set-up the calibration tests and calib_report share: a precision ball, the
// true mount drawn around the configured one, and the sphere scans at eight robot poses.

#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "calib/css_calibration.hpp"
#include "calib_fixtures.hpp"
#include "sim/calibration_scans.hpp"
#include "test/support/ordered_draws.hpp"

namespace rangefit::test {

inline constexpr double kRadius = 25.0;  // a 50 mm precision ball
inline const Eigen::Vector3d kCentre(400.0, -150.0, 80.0);

struct CssMountTruth {
  Eigen::Isometry3d mount;
  double omega_zero = 0.0;
};

// The configured mount off by up to 10 mm (y, z: x = 0 defines the zero, see the header) and
// 3 deg, the zero by up to 3 deg.
inline CssMountTruth perturbed_mount(const hal::CssGeometry& g, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  CssMountTruth t;
  t.mount = calib::nominal_mount(g);
  const double dz = draw(rng), dy = draw(rng);  // in the order of the recorded data
  t.mount.translation() += Eigen::Vector3d(0.0, 10.0 * dy, 10.0 * dz);
  const Eigen::Vector3d w = test::draw3(draw, rng);
  t.mount.linear() =
      t.mount.linear() * Eigen::AngleAxisd(3.0 * kDeg, w.normalized()).toRotationMatrix();
  t.omega_zero = 3.0 * kDeg * draw(rng);
  return t;
}

// Eight robot poses: the sensor 30 mm above the ball's centre along its own axis, looking at it
// from up to 35 deg off vertical and with the wrist turned, as the robot was taught with the
// configured mount; each scan turns the joint through +-5 deg.
inline std::vector<calib::CssSphereScan> css_sphere_scans(const hal::CssGeometry& g,
                                                          const CssMountTruth& truth,
                                                          double sigma_mm, std::uint64_t seed,
                                                          int revolutions = 21) {
  std::vector<calib::CssSphereScan> scans;
  std::vector<double> omega;
  for (int k = 0; k < revolutions; ++k) {
    omega.push_back((-5.0 + 10.0 * k / (revolutions - 1)) * kDeg);
  }
  const Eigen::Isometry3d taught = calib::nominal_mount(g);
  for (int i = 0; i < 8; ++i) {
    Eigen::Isometry3d T_base_css = Eigen::Isometry3d::Identity();
    T_base_css.linear() =
        (Eigen::AngleAxisd(i * 45.0 * kDeg, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd((i % 2 ? 35.0 : 15.0) * kDeg, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(i * 70.0 * kDeg, Eigen::Vector3d::UnitZ()))
            .toRotationMatrix();
    T_base_css.translation() = kCentre + T_base_css.linear() * Eigen::Vector3d(0.0, 0.0, 30.0);
    calib::CssSphereScan scan;
    scan.T_base_joint = T_base_css * taught.inverse();
    for (const auto& s : sim::simulate_css_sphere_scan(
             g, truth.mount, truth.omega_zero, scan.T_base_joint, omega, kCentre, kRadius, sigma_mm,
             1000 * seed + static_cast<unsigned>(i))) {
      scan.samples.push_back({s.omega_rad, s.beam_rad, s.range_mm});
    }
    scans.push_back(std::move(scan));
  }
  return scans;
}

}  // namespace rangefit::test
