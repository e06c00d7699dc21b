#pragma once
// Hand-eye calibration of the Circular Scanning Sensor on the robot's last joint (thesis 4.2.1;
// the thesis leaves it to ref. [12]): from scans of a precision sphere at several robot poses,
// the sensor's mount on the joint and the joint's zero offset, by least squares over every range
// sample of every scan. Model (eq. 4.17 generalised to a full mount):
//   p_base = T_base_joint_i * R_y(omega - omega_zero) * T_joint_css * x_s(beam, range),
// residual |p_base - c| - r for the sphere's centre c (unknown) and radius r (certified),
// divided by the cosine between beam and surface normal (range noise, not surface noise).
//
// A turn of the mount about the joint axis (y) and a change of omega_zero move every sample the
// same way, so they cannot both be estimated; as in eq. 4.17, where t = (0, 0, R), the sensor
// origin is held in the joint's y-z plane (mount x = 0), which defines omega_zero as the joint
// angle at which the sensor origin crosses that plane. Estimated: omega_zero, mount y and z, the
// mount's three rotations and c (9 parameters).

#include <Eigen/Geometry>
#include <span>
#include <string>
#include <vector>

#include "detect/common/levenberg_marquardt.hpp"
#include "hal/css_geometry.hpp"

namespace rangefit::calib {

struct CssSample {
  double omega_rad = 0.0;  // reported joint angle
  double beam_rad = 0.0;   // beam angle (hal::CssGeometry::beam_angle)
  double range_mm = 0.0;
};

struct CssSphereScan {
  Eigen::Isometry3d T_base_joint = Eigen::Isometry3d::Identity();  // from the robot controller
  std::vector<CssSample> samples;
};

struct CssCalibrationOptions {
  double sphere_radius_mm = 25.0;  // certified radius of the reference sphere
  LmOptions lm{
      .max_iterations = 50, .tau = 1e-3, .gradient_tolerance = 1e-12, .step_tolerance = 1e-10};
};

// Parameter order of the covariance: omega_zero (rad), mount y, z (mm), mount rotation about its
// own axes (3, rad), sphere centre (3, mm, base frame).
using Matrix9d = Eigen::Matrix<double, 9, 9>;

struct CssCalibrationResult {
  bool ok = false;
  std::string reason;
  Eigen::Isometry3d T_joint_css = Eigen::Isometry3d::Identity();  // mount x = 0 (see above)
  double omega_zero_rad = 0.0;
  Eigen::Vector3d sphere_centre_mm = Eigen::Vector3d::Zero();
  std::size_t samples = 0;   // fitted
  std::size_t rejected = 0;  // left out as not on the sphere (beyond 4 robust sigma of the fit)
  double rms_mm = 0.0, initial_rms_mm = 0.0;  // residuals as range errors along the beam
  int iterations = 0;
  Matrix9d covariance = Matrix9d::Zero();
  // 1 sigma of what a bore measurement inherits: the sensor origin (joint frame, mm) and the
  // direction of the sensor's z-axis, i.e. a bore axis seen along it (rad), at omega = 0.
  Eigen::Vector3d origin_sigma_mm = Eigen::Vector3d::Zero();
  double axis_sigma_rad = 0.0;
  // The mount as hal::CssGeometry holds it (eta about x, pivot radius along z) and how far the
  // calibrated mount is from that form: the parts the configuration cannot hold.
  double eta_rad = 0.0, pivot_radius_mm = 0.0;
  double mount_off_form_mm = 0.0, mount_off_form_rad = 0.0;
};

// `start`: the configured sensor (eta, pivot radius) as the mount's start; omega_zero_start its
// configured zero. The sensor's own geometry (p_LD, scan circle) is taken as factory-calibrated.
CssCalibrationResult calibrate_css_mount(std::span<const CssSphereScan> scans,
                                         const hal::CssGeometry& start, double omega_zero_start,
                                         const CssCalibrationOptions& options = {});

// The mount of eq. 4.17: rotation eta about x, then the pivot radius along the joint's z.
Eigen::Isometry3d nominal_mount(const hal::CssGeometry& g);

}  // namespace rangefit::calib
