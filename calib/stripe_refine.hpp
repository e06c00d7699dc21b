#pragma once
// The final non-linear step of the stripe calibration (calib/stripe_calibration.hpp): the poses
// of the cameras and the axis direction that put every plane point on its true plane of the
// cube, by the shared Levenberg-Marquardt loop. All cameras triangulate one laser plane, so
// camera k's ranger pose is camera 0's times an in-plane map P_k (a turn about the plane's
// normal y, possibly flipped, and a shift along x and z). Residual of point i of camera k on
// plane j: n_j . (R_0 P_k q_i + t_0 - s_i d) - offset_j, q_i = (x_i, 0, z_i) in camera k's frame.
//
// Parameters, in this order: camera 0's origin in the cell (x, y, z mm), a small rotation of it
// about its own axes (3, rad; R <- R exp(w)), the axis direction's tilt along two unit vectors
// normal to it (2, rad), then per further camera its in-plane shift along its own x and z (mm)
// and its turn about its own y (rad). One camera: the first 8.

#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "calib/calibration_cube.hpp"
#include "detect/common/levenberg_marquardt.hpp"

namespace rangefit::calib {

struct StripePlanePoint {
  Eigen::Vector3d q;  // ranger frame of its camera, y = 0
  double axis_mm = 0.0;
  int plane = 0;   // index into the planes
  int camera = 0;  // index into StripeRig::in_plane
};

// One camera's ranger pose and the axis direction.
struct StripeState {
  Eigen::Isometry3d T_cell_ranger = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  // unit
};

// The cameras of one laser plane.
struct StripeRig {
  Eigen::Isometry3d T_cell_ranger0 = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Isometry3d> in_plane{Eigen::Isometry3d::Identity()};  // P_k, P_0 = I
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();                         // unit

  Eigen::Index parameters() const { return 8 + 3 * static_cast<Eigen::Index>(in_plane.size() - 1); }
  StripeState camera(std::size_t k) const { return {T_cell_ranger0 * in_plane[k], axis}; }
};

using StripeRefinement = LmOutcome<Eigen::Dynamic, StripeRig>;

// planes[k]: the true planes camera k sees (StripePlanePoint::plane indexes them).
StripeRefinement refine_stripe(const StripeRig& start, const std::vector<StripePlanePoint>& pts,
                               std::span<const std::array<CubePlane, 6>> planes,
                               const LmOptions& options);

// d(camera k's parameters)/d(the rig's): 8 x parameters(), camera k's pose as camera 0's is
// parameterised (its origin in the cell, a rotation about its own axes) and the axis tilt. The
// covariance of camera k is G C G^T.
Eigen::MatrixXd camera_jacobian(const StripeRig& rig, std::size_t k);

// In-plane map nearest to T (the relative pose of two cameras of one plane).
Eigen::Isometry3d nearest_in_plane(const Eigen::Isometry3d& T);

// Two unit vectors normal to d (and to each other): the directions the axis may tilt in.
void axis_tangents(const Eigen::Vector3d& d, Eigen::Vector3d& u1, Eigen::Vector3d& u2);

}  // namespace rangefit::calib
