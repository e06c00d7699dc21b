#pragma once
// The final non-linear step of the stripe calibration (calib/stripe_calibration.hpp): the ranger
// pose and the axis direction that put every plane point on its true plane of the cube, by the
// shared Levenberg-Marquardt loop. Residual of point i on plane j:
// n_j . (R q_i + t - s_i d) - offset_j, q_i = (x_i, 0, z_i) in the ranger frame.

#include <Eigen/Geometry>
#include <vector>

#include "calib/calibration_cube.hpp"
#include "detect/common/levenberg_marquardt.hpp"

namespace rangefit::calib {

struct StripePlanePoint {
  Eigen::Vector3d q;  // ranger frame, y = 0
  double axis_mm = 0.0;
  int plane = 0;  // index into the planes
};

struct StripeState {
  Eigen::Isometry3d T_cell_ranger = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  // unit
};

using StripeRefinement = LmOutcome<8, StripeState>;

StripeRefinement refine_stripe(const StripeState& start, const std::vector<StripePlanePoint>& pts,
                               const std::array<CubePlane, 6>& planes, const LmOptions& options);

// Two unit vectors normal to d (and to each other): the directions the axis may tilt in.
void axis_tangents(const Eigen::Vector3d& d, Eigen::Vector3d& u1, Eigen::Vector3d& u2);

}  // namespace rangefit::calib
