#pragma once
// Pose-only Levenberg-Marquardt fit of a superquadric part (thesis 5.1.2): size, shape and taper
// are fixed by the model, the six pose parameters minimise sum (F^eps1 - 1)^2 (eq. 5.1). The
// rotation is updated by a local increment R <- R exp([w]x), so there is no gimbal lock. The
// damping and stopping rules are those of eq. 2.58-2.65 (Madsen/Nielsen/Tingleff).

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <span>

#include "detect/object/superquadric.hpp"

namespace rangefit {

struct PoseFitOptions {
  int max_iterations = 20;           // k_max, eq. 2.65
  double tau = 1e-3;                 // mu_0 = tau max_i (J^T J)_ii, eq. 2.60
  double gradient_tolerance = 1e-9;  // eps' on ||g||_inf, eq. 2.63
  double step_tolerance = 1e-7;      // eps'' on the step, eq. 2.64
};

enum class FitTermination {
  kGradient,       // ||g||_inf <= eps' (eq. 2.63)
  kStep,           // small step (eq. 2.64)
  kMaxIterations,  // k >= k_max (eq. 2.65)
  kTooFewPoints,   // fewer than 6 points: the pose is not determined
  kInvalidInput,   // invalid model, non-finite points or pose
};

struct PoseFitResult {
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
  double measure = 0.0;          // M of eq. 5.2 at the result (rms of F^eps1 - 1)
  double initial_measure = 0.0;  // M at `initial` (the first linearisation's cost)
  int iterations = 0;
  FitTermination termination = FitTermination::kInvalidInput;
  // J^T J of eq. 2.58 at the result, for the increment [dt (world, mm), w (part frame, rad)],
  // and the number of points: covariance() is the pose's covariance from them.
  Eigen::Matrix<double, 6, 6> jtj = Eigen::Matrix<double, 6, 6>::Zero();
  std::size_t points = 0;
  // s^2 (J^T J)^+ with s^2 = sum r^2 / (n - 6), the residual variance. A symmetric part's free
  // directions (a cylinder's spin) move none of its surface and get variance 0. Zero when the fit
  // did not run.
  Eigen::Matrix<double, 6, 6> covariance() const;
  bool ok() const {
    return termination != FitTermination::kTooFewPoints &&
           termination != FitTermination::kInvalidInput;
  }
};

// Refines `initial` (T_world_part) on the points (world frame, mm).
PoseFitResult fit_pose(const Superquadric& sq, std::span<const Eigen::Vector3d> points,
                       const Eigen::Isometry3d& initial, const PoseFitOptions& options = {});

// Eq. 5.2 for the posed part; 0 for no points.
double measure_of_fit(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                      std::span<const Eigen::Vector3d> points);

struct MomentInitOptions {
  int short_iterations = 10;  // iterations of each of the short candidate fits
  int full_iterations = 20;   // iterations of the final fit from the best candidate
  // When set, the part centre is assumed on the far side of the surface seen from here (a
  // single-view scan sees the front of each part); when not, both sides are tried.
  std::optional<Eigen::Vector3d> viewpoint;
  // When set, only candidate poses it accepts (after their short fit) are chosen: a flat patch
  // fits every candidate equally well, and the one picked by M alone may be a part standing
  // through the table when the other would rest on it. None accepted: no fit (not ok()).
  std::function<bool(const Eigen::Isometry3d&)> admissible;
  // When set, an admissible candidate it accepts wins over one it does not, whatever their M
  // (e.g. a part that rests on the table where the part must).
  std::function<bool(const Eigen::Isometry3d&)> preferred;
  // When set, each candidate is moved by it before its short fit; it gets the candidate and the
  // patch's normal. A flat patch does not place a part along itself: a patch high on a standing
  // box's face starts the box floating, and the lying box that its end face would make rests in
  // the same place; slid down the face onto the table, the one whose face does not reach the
  // patch misfits it.
  std::function<Eigen::Isometry3d(const Eigen::Isometry3d&, const Eigen::Vector3d&)> settle;
};

// Thesis 5.1.2: the z-axis is tried along each of the three central-moment directions of the
// points (with the centre set back from the surface patch by the matching size), a short fit is
// run for each, and the best one (smallest M) is fitted to convergence.
PoseFitResult fit_pose_from_moments(const Superquadric& sq, std::span<const Eigen::Vector3d> points,
                                    const MomentInitOptions& init = {},
                                    const PoseFitOptions& options = {});

}  // namespace rangefit
