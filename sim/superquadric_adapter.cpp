#include "sim/superquadric_adapter.hpp"

#include "sim/superquadric_raycast.hpp"

namespace rangefit::sim {

std::optional<ShapeHit> intersect_superquadric_shape(const SuperquadricShape& shape,
                                                     const Eigen::Isometry3d& T_world_object,
                                                     const Eigen::Vector3d& origin,
                                                     const Eigen::Vector3d& dir, double t_min,
                                                     double t_max) {
  const auto t = intersect_superquadric(shape.model, T_world_object, origin, dir, t_max, t_min);
  if (!t) return std::nullopt;
  const Eigen::Vector3d p = origin + *t * dir;
  return ShapeHit{*t, superquadric_normal(shape.model, T_world_object, p)};
}

}  // namespace rangefit::sim
