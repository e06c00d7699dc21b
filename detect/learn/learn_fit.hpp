#pragma once
// The full superquadric fit of model learning (thesis 2.1.3, 2.2): size a1..a3, shape eps1 eps2,
// taper kx ky and the pose, thirteen parameters, by Levenberg-Marquardt
// (detect/levenberg_marquardt.hpp, the loop the pose fit runs) on the residuals
//
//   r_i = sqrt(1 + lambda a1 a2 a3 / V0) d_i,   d_i = f_i / |df_i/dq|,
//   f_i = |q_i| (1 - G(q_i)^-1/2)
//
// f_i is the radial distance of the point q_i (part frame) from the surface, from the metric
// G = F^eps1 of eq. 5.1 (thesis 2.2.1: the radial Euclidean distance fits better than the
// algebraic one); d_i, f_i over its gradient's length, is the distance along the normal to first
// order (detect/learn/learn_surface.hpp: f alone inflates the noise near a tapered part's narrow
// end many times over, and a fit on it blunts a pyramid's tip). The factor 1 / |df/dq| is held
// within one linearisation. The volume term after Solina and Bajcsy [116] (the note under
// eq. 5.1) prefers the smaller of the superquadrics that explain the points equally, which keeps
// a single-view fit from growing into the unseen side. It is 1 + lambda V / V0 rather than
// Solina's V / V0 because with a true distance that factor alone would let a part shrink to
// nothing (V -> 0 drives every residual to 0). V0 is common to all starts, so their costs compare.
// Sizes move in log steps, shape and taper additively, clamped to their valid ranges; the pose by
// R <- R exp([w]x) as in the pose fit. The pose columns of the Jacobian are analytic (the
// metric's gradient), the seven model columns forward differences through the vectorised
// metric (SuperquadricMetric::values).

#include <Eigen/Geometry>
#include <optional>
#include <span>

#include "detect/object/superquadric.hpp"

namespace rangefit {

struct PosedSuperquadric {
  Superquadric shape;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
};

// What each point contributes to the fit. The metric F^eps1 - 1 shrinks with the distance of a
// point from the centre, so from one view it prefers parts whose centre lies far behind the
// seen surface (a sphere's cap is fitted by an elongated egg with a smaller M); the distances do
// not. The radial distance f_i pulls a start far from the points into place as surely as the
// distance d_i (a mug's handle started from its moments reaches its shape on f_i, and stops in a
// wrong shape on d_i), but it biases the end of the fit where it overstates the distance.
enum class FitResidual {
  kMetric,    // F^eps1 - 1
  kRadial,    // f_i, mm
  kDistance,  // d_i, mm
};

struct ShapeFitOptions {
  int max_iterations = 100;
  double step_tolerance = 1e-6;   // eq. 2.64, relative to the centre's distance from the origin
  double reference_volume = 1.0;  // V0 of the residual, mm^3 (> 0)
  double volume_weight = 0.05;    // lambda: r_i x sqrt(1 + lambda a1 a2 a3 / V0); 0: no volume term
  bool fit_taper = true;          // false: kx, ky stay as given
  FitResidual residual = FitResidual::kDistance;
  double min_eps = 0.1, max_eps = 2.0;
  double max_taper = 1.0;  // |kx|, |ky| at most this
  double min_size_mm = 0.5;
  // The table the part rests on, n . x = offset with unit n towards the part: the part's lowest
  // point along n (exact for an untapered part, and for any part standing on an end: learn_fit.cpp
  // extreme_point) is held on the table by one residual weighted like support_weight x the points.
  // A single view never sees where the part touches the table, and without it the hidden side
  // is free: a cone's size, taper and centre trade off (its base floated 0.3 mm above the table,
  // 2 % off), a sphere whose fitted axis turned away from the vertical grew an egg's unseen half.
  std::optional<Eigen::Vector4d> support_plane;  // (n, offset)
  double support_weight = 0.1;
};

struct ShapeFitResult {
  PosedSuperquadric part;
  double cost = 0.0;     // 0.5 sum r^2 at the result (comparable between starts)
  double measure = 0.0;  // M of eq. 5.2 (rms of F^eps1 - 1, no volume factor)
  int iterations = 0;
  bool ok = false;  // false: fewer than 13 points or invalid input
};

// Height of the part's lowest point above the plane n . x = offset (unit n towards the part),
// exact as for ShapeFitOptions::support_plane.
double support_height(const PosedSuperquadric& part, const Eigen::Vector4d& plane);

// Fits the part to the points (world frame, mm) from `initial`.
ShapeFitResult fit_superquadric(std::span<const Eigen::Vector3d> points,
                                const PosedSuperquadric& initial,
                                const ShapeFitOptions& options = {});

}  // namespace rangefit
