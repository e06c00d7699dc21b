#pragma once
// How well a learnt part is supported by its points: the rms radial distance of the points
// from the surface (along the ray from the centre, the radial Euclidean distance of thesis
// 2.2.1), and the share of the part's surface area that has measured points near it (a single
// view sees at most about half of a part; the rest of the model is inferred).

#include <Eigen/Geometry>
#include <span>

#include "detect/object/superquadric.hpp"

namespace rangefit {

// rms over the points of |q| |1 - G(q)^(-1/2)| (q in the part frame): exact along the ray for
// untapered parts, whose G scales with the square of the distance from the centre.
double radial_rms_mm(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                     std::span<const Eigen::Vector3d> points);

// Share of the surface area (sampled on a latitude/longitude grid of eq. 2.14, each cell weighted
// by its area) with a point within tolerance_mm.
double visible_share(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                     std::span<const Eigen::Vector3d> points, double tolerance_mm);

}  // namespace rangefit
