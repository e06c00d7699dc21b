#pragma once
// Calibration of the mobile scanning head (thesis 5.2.1, eq. 5.7) from sweeps over the hollow
// calibration cube (thesis 3.2.2) at several tilt angles: the translations t_s (sensor origin
// from the pan-tilt centre, sensor axes) and t_w (pan-tilt centre in the world) and the zero
// offsets of the pan and tilt encoders, i.e. every field of hal::PanTiltGeometry that places
// the ranger. Eq. 5.7 has the sensor axes parallel to the unit's at pan = tilt = 0, so the
// mount's turn is the two zero offsets (a turn about the laser plane's normal is the tilt zero,
// one about the laser line the pan zero).
//
// As in the stripe calibration (calib/stripe_calibration.hpp, thesis 3.2.3), each round maps the
// raw profiles to the world with the current estimate, extracts the cube's six planes in every
// sweep by normal-constrained RANSAC (calib/plane_extraction.hpp) and then, since eq. 5.7 has no
// linear form, moves the estimate by Levenberg-Marquardt (detect/levenberg_marquardt.hpp) so
// every plane point lies on its true plane of the cube. Three rounds: the later ones extract
// the planes from a nearly exact cloud. Several tilts are needed: with pan alone the part of
// t_s along the pan axis cannot be told from t_w.

#include <Eigen/Geometry>
#include <array>
#include <span>
#include <string>
#include <vector>

#include "calib/calibration_cube.hpp"
#include "calib/plane_extraction.hpp"
#include "detect/common/levenberg_marquardt.hpp"
#include "hal/pan_tilt_geometry.hpp"
#include "hal/samples.hpp"

namespace rangefit::calib {

// One sweep: the raw profiles (ranger frame x, z) with the reported pan and tilt of each.
struct PanTiltSweep {
  std::span<const hal::RangerProfile> profiles;
  std::span<const hal::PanTiltSample> angles;  // one per profile
};

struct PanTiltCalibrationInput {
  std::vector<PanTiltSweep> sweeps;  // at two or more tilt angles
  CalibrationCube cube;
  Eigen::Isometry3d T_world_cube = Eigen::Isometry3d::Identity();  // where the fixture holds it
};

struct PanTiltCalibrationOptions {
  int rounds = 3;
  double normal_radius_mm = 4.0;  // PCA patch for the points' normals
  double crop_margin_mm = 60.0;   // points further than this outside the cube's sphere are left out
  PlaneExtractionOptions planes;
  LmOptions lm{
      .max_iterations = 40, .tau = 1e-3, .gradient_tolerance = 1e-12, .step_tolerance = 1e-11};
};

// Parameters of the refinement and of the covariance, in this order: t_s (3, mm), t_w (3, mm),
// pan zero, tilt zero (rad).
using PanTiltMatrix8d = Eigen::Matrix<double, 8, 8>;

struct PanTiltRound {
  std::size_t plane_points = 0;  // over all sweeps
  double rms_mm = 0.0;           // their distance to the true planes after this round
};

struct PanTiltCalibrationResult {
  bool ok = false;
  std::string reason;             // why not, when !ok
  hal::PanTiltGeometry geometry;  // the start with t_s, t_w and the zeros replaced
  std::vector<PanTiltRound> rounds;
  std::size_t points = 0;       // plane points of the last round
  double rms_mm = 0.0;          // their rms distance to the true planes
  double initial_rms_mm = 0.0;  // the first round's points under the start values
  int lm_iterations = 0;        // over all rounds
  PanTiltMatrix8d covariance = PanTiltMatrix8d::Zero();  // sigma^2 (J^T J)^-1
  Eigen::Vector3d t_s_sigma_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d t_w_sigma_mm = Eigen::Vector3d::Zero();
  Eigen::Vector2d zero_sigma_rad = Eigen::Vector2d::Zero();  // pan, tilt
};

// `start`: the configured head (its ranger and the rough t_s, t_w and zeros).
PanTiltCalibrationResult calibrate_pan_tilt(const PanTiltCalibrationInput& input,
                                            const hal::PanTiltGeometry& start,
                                            const PanTiltCalibrationOptions& options = {});

}  // namespace rangefit::calib
