#pragma once
// Calibration of the laser-stripe cell from one sweep over the hollow calibration cube (thesis
// 3.2.3), for one camera or several that triangulate the same laser plane (fig. 3.6b, cameras
// even on both sides of it). Input per camera: the raw profiles (ranger frame x, z of
// hal::RangerProfile) with the axis position of each and a rough start (its configured layout,
// off by up to ~10 mm and a few degrees); the cube and where its fixture holds it on the table.
// Output per camera: its ranger pose in the cell and the axis direction (the
// [fusion.stripe_cell] fields), with residuals and covariance.
//
// Each round maps a camera's raw points to the table with its current estimate, extracts the
// cube's six planes by normal-constrained RANSAC (calib/plane_extraction.hpp), intersects
// triples to the eight corners and takes their raw coordinates (x_c, z_c, s_c) back through the
// estimate. Then, as the thesis does, first the camera-independent geometry: the laser plane
// n . X = h and k = n . d from the corners' piercing points X_c + s_c d (linear, null space);
// then the mapping M of the sensor plane onto the laser plane together with the in-plane part
// of d (linear least squares). The ranger reports metric laser-plane coordinates, so M is
// affine and its nearest rigid map is the ranger pose. Three rounds calibrate each camera on
// its own; with several cameras a fourth averages the piercing points over them, so they share
// one laser plane and axis ("improves the local matching of the point clouds"). A final
// Levenberg-Marquardt refinement (detect/levenberg_marquardt.hpp, calib/stripe_refine.hpp)
// minimises every plane point's distance to its true plane, over all cameras at once.

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

// One camera of a rig: its sweep of the cube (all cameras see the cube where the fixture holds
// it; their sweeps may be one or several) and its configured layout.
struct StripeCameraInput {
  std::span<const hal::RangerProfile> profiles;
  std::span<const double> axis_mm;  // one per profile
  hal::StripeCellGeometry start;
};

struct StripeRigInput {
  std::vector<StripeCameraInput> cameras;
  CalibrationCube cube;
  Eigen::Isometry3d T_table_cube = Eigen::Isometry3d::Identity();
};

struct StripeRigResult {
  bool ok = false;
  std::string reason;  // why not, when !ok; names the camera
  // Per camera: its geometry, rounds, plane points and their rms, and the covariance of its
  // pose and the axis (the joint covariance's share, 8 x 8 as for one camera).
  std::vector<StripeCalibrationResult> cameras;
  std::size_t points = 0;
  double rms_mm = 0.0, initial_rms_mm = 0.0;
  int lm_iterations = 0;
  Eigen::MatrixXd covariance;  // of calib/stripe_refine.hpp's parameters
};

// The cameras share the laser plane and the axis: camera k's pose is fitted as camera 0's times
// an in-plane map. One camera gives calibrate_stripe_cell's result.
StripeRigResult calibrate_stripe_rig(const StripeRigInput& input,
                                     const StripeCalibrationOptions& options = {});

// Roll, pitch, yaw of R = Rz(yaw) Ry(pitch) Rx(roll) (hal's convention), roll taken within pi of
// `near` so a calibrated angle stays next to the configured one.
Eigen::Vector3d rpy_of(const Eigen::Matrix3d& R, const Eigen::Vector3d& near);

}  // namespace rangefit::calib
