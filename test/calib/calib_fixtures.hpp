#pragma once
// Shared set-ups of the calibration tests: a true cell drawn around the configured one (up to
// 10 mm and 3 deg off, seeded), the calibration cube where its fixture holds it, and the sweep.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "calib/stripe_calibration.hpp"
#include "detect/common/angles.hpp"
#include "hal/pan_tilt_geometry.hpp"
#include "hal/samples.hpp"
#include "hal/stripe_geometry.hpp"
#include "sim/calibration_scans.hpp"

namespace rangefit::test {

// The cube held on a corner with its centre at `centre`: its body diagonal along the unit
// vector b, turned 20 deg about it so that no edge lies in the laser plane.
inline Eigen::Isometry3d cube_on_corner(const Eigen::Vector3d& b, const Eigen::Vector3d& centre) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(20.0 * kDeg, b) *
                Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::Ones().normalized(), b))
                   .toRotationMatrix();
  T.translation() = centre;
  return T;
}

// Cube body diagonal between the laser (down the fan) and the camera (baseline along -y of the
// cell).
inline Eigen::Isometry3d cube_on_table() {
  return cube_on_corner(Eigen::Vector3d(0.0, -std::sin(18.0 * kDeg), std::cos(18.0 * kDeg)),
                        Eigen::Vector3d(5.0, 3.0, 130.0));
}

// Uniform in [-1, 1].
inline double draw(std::mt19937_64& rng) {
  return std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
}

inline hal::StripeCellGeometry perturbed_cell(const hal::StripeCellGeometry& nominal,
                                              std::uint64_t seed, double mm = 10.0,
                                              double deg = 3.0) {
  std::mt19937_64 rng(seed);
  hal::StripeCellGeometry g = nominal;
  for (int i = 0; i < 3; ++i) g.ranger_position_cell_mm[i] += mm * draw(rng);
  for (int i = 0; i < 3; ++i) g.ranger_rpy_cell_rad[i] += deg * kDeg * draw(rng);
  const double tz = draw(rng), tx = draw(rng);  // in the order of the recorded data
  const Eigen::Vector3d tilt(deg * kDeg * tx, 0.0, deg * kDeg * tz);
  g.axis_direction_cell =
      (Eigen::AngleAxisd(tilt.x(), Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(tilt.z(), Eigen::Vector3d::UnitZ()) * nominal.axis_direction_cell)
          .normalized();
  return g;
}

// The pan-tilt head's configured layout: the ranger 60 mm in front of the unit's centre and
// 50 mm below its pan axis (t_s), the unit at the world origin.
inline hal::PanTiltGeometry configured_head() {
  hal::PanTiltGeometry g;
  g.t_s_mm = Eigen::Vector3d(0.0, -50.0, 60.0);
  return g;
}

// The true head: t_s and t_w up to `mm` off in every component, both zeros up to `deg`.
inline hal::PanTiltGeometry perturbed_head(const hal::PanTiltGeometry& nominal, std::uint64_t seed,
                                           double mm = 10.0, double deg = 3.0) {
  std::mt19937_64 rng(seed);
  hal::PanTiltGeometry g = nominal;
  for (int i = 0; i < 3; ++i) g.t_s_mm[i] += mm * draw(rng);
  for (int i = 0; i < 3; ++i) g.t_w_mm[i] += mm * draw(rng);
  g.pan_zero_rad += deg * kDeg * draw(rng);
  g.tilt_zero_rad += deg * kDeg * draw(rng);
  return g;
}

// The cube 750 mm in front of the head (its world z), body diagonal between the laser (at the
// head) and the camera (baseline along +y).
inline Eigen::Isometry3d cube_before_head() {
  return cube_on_corner(Eigen::Vector3d(0.0, std::sin(15.0 * kDeg), -std::cos(15.0 * kDeg)),
                        Eigen::Vector3d(4.0, -6.0, 750.0));
}

// Reported angles of one sweep: pan -12..12 deg in `step_deg` at a held tilt.
inline std::vector<hal::PanTiltSample> pan_sweep(double tilt_deg, double step_deg = 0.1) {
  std::vector<hal::PanTiltSample> out;
  for (double p = -12.0; p <= 12.0 + 1e-9; p += step_deg) {
    hal::PanTiltSample s;
    s.pan_rad = p * kDeg;
    s.tilt_rad = tilt_deg * kDeg;
    out.push_back(s);
  }
  return out;
}

inline double angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

// One stripe-cell sweep of the calibration cube by the `truth` cell, a profile every step_mm
// of the axis.
struct Sweep {
  std::vector<double> axis;
  std::vector<hal::RangerProfile> profiles;
};

inline Sweep stripe_cube_sweep(const hal::StripeCellGeometry& truth, const sim::RangerNoise& noise,
                               double step_mm = 1.0,
                               const Eigen::Isometry3d& T_table_cube = cube_on_table()) {
  const calib::CalibrationCube cube;
  Sweep s;
  for (double a = 60.0; a <= 340.0; a += step_mm) s.axis.push_back(a);
  const sim::Scene scene =
      sim::calibration_cube_scene(cube.edge_mm, cube.bar_mm, T_table_cube, true);
  s.profiles = sim::simulate_stripe_sweep(scene, truth, s.axis, noise);
  return s;
}

// Cube body diagonal straight up towards the laser: cameras on both sides of the laser plane
// see its three outer faces.
inline Eigen::Isometry3d cube_between_cameras() {
  return cube_on_corner(Eigen::Vector3d::UnitZ(), Eigen::Vector3d(5.0, 3.0, 130.0));
}

// A second camera of camera a's laser plane, on the other side of it, that reports its points
// in its own frame of the plane: T_cell_ranger = a's T_cell_ranger P, P a turn about the plane's
// normal y and a shift along x and z, or that after turning the frame over (y reversed: the
// camera is then on its own +y side).
inline hal::StripeCellGeometry other_side_camera(const hal::StripeCellGeometry& a,
                                                 const Eigen::Isometry3d& P) {
  hal::StripeCellGeometry b = a;
  b.ranger.baseline_mm = P.linear()(1, 1) < 0.0 ? a.ranger.baseline_mm : -a.ranger.baseline_mm;
  const Eigen::Isometry3d T = a.T_cell_ranger() * P;
  b.ranger_position_cell_mm = T.translation();
  b.ranger_rpy_cell_rad = calib::rpy_of(T.linear(), a.ranger_rpy_cell_rad);
  return b;
}

// That camera's sweep: camera a's laser seen from the other side, in the frame P.
inline Sweep other_side_sweep(const hal::StripeCellGeometry& a, const Eigen::Isometry3d& P,
                              const sim::RangerNoise& noise, double step_mm,
                              const Eigen::Isometry3d& T_table_cube) {
  hal::StripeCellGeometry seen_from = a;
  seen_from.ranger.baseline_mm = -a.ranger.baseline_mm;
  Sweep s = stripe_cube_sweep(seen_from, noise, step_mm, T_table_cube);
  const Eigen::Isometry3d to_b = P.inverse();
  for (hal::RangerProfile& p : s.profiles) {
    for (std::size_t k = 0; k < p.x_mm.size(); ++k) {
      const Eigen::Vector3d q = to_b * Eigen::Vector3d(p.x_mm[k], 0.0, p.z_mm[k]);
      p.x_mm[k] = static_cast<float>(q.x());
      p.z_mm[k] = static_cast<float>(q.z());
    }
  }
  return s;
}

// Camera b's frame of the laser plane against camera a's.
inline Eigen::Isometry3d b_in_a() {
  Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
  P.linear() = Eigen::AngleAxisd(2.0 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  P.translation() = Eigen::Vector3d(6.0, 0.0, -5.0);
  return P;
}

// Two cameras of one laser plane, one on each side of it, the truth drawn from `seed`, and
// their sweeps of the cube standing on a corner between them.
struct Rig {
  hal::StripeCellGeometry truth_a, truth_b;
  Sweep a, b;
};

inline Rig two_sided_rig(std::uint64_t seed, const sim::RangerNoise& noise) {
  Rig r;
  r.truth_a = perturbed_cell(hal::StripeCellGeometry{}, seed);
  r.truth_b = other_side_camera(r.truth_a, b_in_a());
  r.a = stripe_cube_sweep(r.truth_a, noise, 2.0, cube_between_cameras());
  sim::RangerNoise other = noise;
  other.seed += 1000;
  r.b = other_side_sweep(r.truth_a, b_in_a(), other, 2.0, cube_between_cameras());
  return r;
}

// Calibrated together, both starting from the configured layout: b the same pose as a, on the
// other side.
inline calib::StripeRigResult calibrate_rig(const Sweep& a, const Sweep& b) {
  const hal::StripeCellGeometry nominal;
  calib::StripeRigInput in;
  in.cameras.push_back({a.profiles, a.axis, nominal});
  in.cameras.push_back(
      {b.profiles, b.axis, other_side_camera(nominal, Eigen::Isometry3d::Identity())});
  in.T_table_cube = cube_between_cameras();
  return calib::calibrate_stripe_rig(in);
}

// Squared errors of calibrated ranger poses in units of their reported sigmas, over the
// position's and the rotation's three axes: their mean is 1 when the covariance is right.
struct NormalisedErrors {
  double z2 = 0.0;
  int count = 0;
  void add(const calib::StripeCalibrationResult& r, const hal::StripeCellGeometry& truth) {
    const Eigen::Vector3d dp = r.geometry.ranger_position_cell_mm - truth.ranger_position_cell_mm;
    const Eigen::AngleAxisd w(truth.T_cell_ranger().linear().transpose() *
                              r.geometry.T_cell_ranger().linear());
    const Eigen::Vector3d dw = w.angle() * w.axis();
    for (int i = 0; i < 3; ++i) {
      z2 += std::pow(dp[i] / r.position_sigma_mm[i], 2) +
            std::pow(dw[i] / r.rotation_sigma_rad[i], 2);
      count += 2;
    }
  }
  double mean() const { return count > 0 ? z2 / count : 0.0; }
};

// The stripe cell calibrated from that sweep, starting from `start` (the configured cell).
inline calib::StripeCalibrationResult calibrate(const Sweep& s,
                                                const hal::StripeCellGeometry& start) {
  calib::StripeCalibrationInput in;
  in.profiles = s.profiles;
  in.axis_mm = s.axis;
  in.T_table_cube = cube_on_table();
  return calib::calibrate_stripe_cell(in, start);
}

}  // namespace rangefit::test
