#pragma once
// Calibration of the laser-stripe cell from one sweep over the hollow calibration cube (thesis
// 3.2.3). Input: the raw profiles (ranger frame x, z of hal::RangerProfile) with the axis
// position of each, the cube and where its fixture holds it on the table, and a rough start (the
// configured layout, off by up to ~10 mm and a few degrees). Output: the ranger pose in the cell
// and the axis direction (the [fusion.stripe_cell] fields), with residuals and covariance.
//
// Each round maps the raw points to the table with the current estimate, extracts the cube's six
// planes by normal-constrained RANSAC (calib/plane_extraction.hpp), intersects triples to the
// eight corners and takes their raw coordinates (x_c, z_c, s_c) back through the estimate. Then,
// as the thesis does, first the camera-independent geometry: the laser plane n . X = h and
// k = n . d from the corners' piercing points X_c + s_c d (linear, null space); then the
// mapping M of the sensor plane onto the laser plane together with the in-plane part of d (linear
// least squares). The ranger reports metric laser-plane coordinates, so M is affine and its
// nearest rigid map is the ranger pose. Three rounds; a final Levenberg-Marquardt refinement
// (detect/levenberg_marquardt.hpp) minimises every plane point's distance to its true plane.

#include <Eigen/Geometry>
#include <array>
#include <span>
#include <string>
#include <vector>

#include "calib/calibration_cube.hpp"
#include "calib/plane_extraction.hpp"
#include "detect/common/levenberg_marquardt.hpp"
#include "hal/samples.hpp"
#include "hal/stripe_geometry.hpp"

namespace rangefit::calib {

struct StripeCalibrationOptions {
  int rounds = 3;                 // thesis: "3 iterations mostly suffice"
  double normal_radius_mm = 4.0;  // PCA patch for the points' normals
  double crop_margin_mm = 40.0;   // points further than this outside the cube's sphere are left out
  PlaneExtractionOptions planes;
  LmOptions lm{
      .max_iterations = 30, .tau = 1e-3, .gradient_tolerance = 1e-12, .step_tolerance = 1e-10};
};

// Parameters of the refinement and of the covariance, in this order: the ranger origin in the
// cell (x, y, z mm), a small rotation of the ranger about its own axes (3, rad; R <- R exp(w)),
// and the axis direction's tilt along two unit vectors normal to it (2, rad).
using Matrix8d = Eigen::Matrix<double, 8, 8>;

struct StripeRound {
  double corner_rms_mm = 0.0;  // true corners vs the raw corners mapped with this round's result
  std::array<std::size_t, 6> plane_points{};
  std::array<double, 6> plane_rms_mm{};  // planarity of each extracted plane
};

struct StripeCalibrationResult {
  bool ok = false;
  std::string reason;                // why not, when !ok
  hal::StripeCellGeometry geometry;  // the start with the calibrated fields replaced
  std::vector<StripeRound> rounds;
  std::size_t points = 0;       // plane points of the refinement
  double rms_mm = 0.0;          // their rms distance to the true planes after it
  double initial_rms_mm = 0.0;  // ... before it (after the linear rounds)
  int lm_iterations = 0;
  Matrix8d covariance = Matrix8d::Zero();  // sigma^2 (J^T J)^-1, sigma from the residuals
  Eigen::Vector3d position_sigma_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_sigma_rad = Eigen::Vector3d::Zero();  // about the ranger's axes
  Eigen::Vector2d axis_sigma_rad = Eigen::Vector2d::Zero();
};

struct StripeCalibrationInput {
  std::span<const hal::RangerProfile> profiles;
  std::span<const double> axis_mm;  // one per profile
  CalibrationCube cube;
  Eigen::Isometry3d T_table_cube = Eigen::Isometry3d::Identity();  // where the fixture holds it
};

StripeCalibrationResult calibrate_stripe_cell(const StripeCalibrationInput& input,
                                              const hal::StripeCellGeometry& start,
                                              const StripeCalibrationOptions& options = {});

// Roll, pitch, yaw of R = Rz(yaw) Ry(pitch) Rx(roll) (hal's convention), roll taken within pi of
// `near` so a calibrated angle stays next to the configured one.
Eigen::Vector3d rpy_of(const Eigen::Matrix3d& R, const Eigen::Vector3d& near);

}  // namespace rangefit::calib
