#pragma once
// How far points lie from a learnt part's surface, and how much of the surface they cover.
//
// The distance is the radial distance of thesis 2.2.1, f = |q| (1 - G(q)^-1/2) for a point q in
// the part frame, divided by the length of its gradient: f / |df/dq|. Along the ray from the
// centre f is exact for an untapered part, but it overstates the distance by 1 / cos of the
// angle between that ray and the surface normal; near a tapered part's narrow end it is many
// times the distance, because the taper is undone before G is taken (a pyramid's tip: a point
// 0.1 mm off a face reads as 2-3 mm). Dividing by the gradient's length turns it into the
// distance along the normal to first order, on any part. A fit on f itself blunts a sharp tip to
// shrink those inflated residuals of the noise there; on f / |df/dq| the truth is the minimum.
// The share of the surface covered tells how much of the part was seen (a single view sees at
// most about half of it; the rest of the model is inferred).

#include <Eigen/Geometry>
#include <span>

#include "detect/object/superquadric.hpp"

namespace rangefit {

// The radial distance f = |q| (1 - G^-1/2) (mm, positive outside) from G(q) and |q|.
double radial_distance(double g, double q_norm);

// The radial distance f (mm, positive outside) and its gradient df/dq at q (part frame), from
// G(q) and dG/dq (SuperquadricMetric::value_and_gradient).
struct RadialDistance {
  double f = 0.0;
  Eigen::Vector3d df_dq = Eigen::Vector3d::Zero();
  // 1 / |df/dq|: the factor that turns f into the distance along the normal.
  double normalising() const;
};
RadialDistance radial_distance(double g, const Eigen::Vector3d& dg_dq, const Eigen::Vector3d& q);

// Distance of q (part frame) from the surface, f / |df/dq| (mm, positive outside). Near the
// surface it equals the detector's (G - 1) / |dG/dq| (detect/object/superquadric.hpp) to first
// order; away from it, where a fit starts, it stays the radial distance, while (G - 1) / |dG/dq|
// halves an outside point's distance and diverges towards the centre.
double radial_surface_distance(const SuperquadricMetric& metric, const Eigen::Vector3d& q);

// rms of radial_surface_distance over the points (world frame).
double surface_rms_mm(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                      std::span<const Eigen::Vector3d> points);

// Share of the surface area (sampled on a latitude/longitude grid of eq. 2.14, each cell weighted
// by its area) with a point within tolerance_mm.
double visible_share(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                     std::span<const Eigen::Vector3d> points, double tolerance_mm);

}  // namespace rangefit
