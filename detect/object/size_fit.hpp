#pragma once
// The part's size let free: the pose and two scale factors of the model (across its axis, a1
// and a2 together; along it, a3) fitted by Levenberg-Marquardt
// (detect/common/levenberg_marquardt.hpp) to the points' distances from the surface, with the
// scales' standard errors from the fit's covariance. The size evidence of the object detector
// (object_hypotheses.hpp size_evidence): a look-alike 4 % larger or smaller wants its own size
// whatever its point count, and the standard error says whether the points determine it at all (a
// box seen on one face does not).
//
// The residual of point i is sqrt(w_i) (G_i - 1) / |grad G_i|, its distance from the surface in
// mm to first order. |grad G_i| and the robust weight w_i = 1 / (1 + (d_i / c)^2) (Cauchy, d_i
// its distance at the start of the round) are held fixed within a round of iterations and
// recomputed between rounds, so the costs the LM compares stay those of one function. A tapered
// part scales like an untapered one: its taper works on z / a3, so G(q; a1 sx, a2 sx, a3 sz) =
// G(qx / sx, qy / sx, qz / sz; a) and the scales' Jacobian columns follow from the gradient.

#include <Eigen/Geometry>
#include <limits>
#include <optional>
#include <span>

#include "detect/object/superquadric.hpp"

namespace rangefit {

struct SizeFitOptions {
  bool free_size = true;       // false: the pose alone, at the model's size
  bool free_rotation = true;   // false: the orientation held (a ball's axis, set by the caller)
  int rounds = 6;              // weight updates
  int iterations = 8;          // LM iterations per round
  double cauchy_mm = 1.0;      // c of the robust weight (at least the noise's few sigma)
  double max_log_scale = 0.4;  // scales held within exp(+-this) of the model's
  // The table the part rests on, n . x = offset with unit n towards the part: the height of its
  // lowest point above it (of its inscribed ellipsoid: exact for a part resting on a face or
  // along its axis) is held within [-support_below_mm, support_above_mm] by one residual, the
  // excess weighted like support_weight x the points. A single view does not see where the part
  // touches the table: without it a standing can's height grows into the table unseen, and a
  // smaller cone set higher fits a cone's flank as well. Where the bound holds the part, it is
  // part of the standard errors (the table places the size), where it does not, not.
  std::optional<Eigen::Vector4d> support_plane;
  double support_weight = 0.1;
  double support_below_mm = 0.0, support_above_mm = 0.0;
};

struct SizeFit {
  bool ok = false;  // false: too few points (fewer than 9) or invalid input
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
  double across = 1.0, along = 1.0;  // the model's a1, a2 and a3 times these fit best
  // Standard errors of log(across) and log(along): about the relative error of the scale. Infinite
  // when the points leave the scale free (a direction of the fit they do not constrain).
  double across_sigma = std::numeric_limits<double>::infinity();
  double along_sigma = std::numeric_limits<double>::infinity();
  double rms_mm = 0.0;  // weighted rms distance from the fitted surface
  // The same for the model's own size, its pose fitted again from this one's with the same weights.
  double model_rms_mm = 0.0;
};

SizeFit fit_size(const Superquadric& part, std::span<const Eigen::Vector3d> points,
                 const Eigen::Isometry3d& initial, const SizeFitOptions& options = {});

}  // namespace rangefit
