#pragma once
// Exact ray intersections (in double) with the analytic primitives of sim/scene.hpp, and the
// distance of a point to their surfaces (for ground-truth checks). The ray caster uses Embree only
// to find which object a ray hits first; the hit point itself is recomputed here, so simulated
// points lie on analytic surfaces to ~1e-9 mm, not to Embree's float precision.

#include <Eigen/Geometry>
#include <optional>

#include "sim/scene.hpp"

namespace rangefit::sim {

struct ShapeHit {
  double t = 0.0;          // ray parameter (mm when dir is unit)
  Eigen::Vector3d normal;  // unit outward surface normal, world frame
};

// First intersection with t in (t_min, t_max] of origin + t*dir (world frame, dir unit). Meshes
// return nullopt here (they are intersected as triangles).
std::optional<ShapeHit> intersect_shape(const Shape& shape, const Eigen::Isometry3d& T_world_object,
                                        const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                        double t_min, double t_max);

// Unsigned distance of a world point to the shape's surface, mm; NaN for meshes and
// superquadrics (no closed form).
double surface_distance(const Shape& shape, const Eigen::Isometry3d& T_world_object,
                        const Eigen::Vector3d& p_world);

// Axis-aligned bounds of the shape in its object frame (meshes: of their vertices).
Eigen::AlignedBox3d local_bounds(const Shape& shape);

// Exact ray/triangle intersection (Moeller-Trumbore in double); t in (t_min, t_max].
std::optional<double> intersect_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c, const Eigen::Vector3d& origin,
                                         const Eigen::Vector3d& dir, double t_min, double t_max);

}  // namespace rangefit::sim
