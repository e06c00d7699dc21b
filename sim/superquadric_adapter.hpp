#pragma once
// Bridges the scene's SuperquadricShape to the object engineer's exact ray/superquadric
// intersection (sim/superquadric_raycast.hpp), so analytic_shapes.cpp has one call for it.

#include <Eigen/Geometry>
#include <optional>

#include "sim/analytic_shapes.hpp"

namespace rangefit::sim {

std::optional<ShapeHit> intersect_superquadric_shape(const SuperquadricShape& shape,
                                                     const Eigen::Isometry3d& T_world_object,
                                                     const Eigen::Vector3d& origin,
                                                     const Eigen::Vector3d& dir, double t_min,
                                                     double t_max);

}  // namespace rangefit::sim
