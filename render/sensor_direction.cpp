#include "render/sensor_direction.hpp"

#include <Eigen/Geometry>

namespace rangefit::render {

std::optional<Eigen::Vector3d> toward_scan_sensor(const SensorView& view,
                                                  const Eigen::Vector3d& target) {
  if (view.kind == SensorView::Kind::kUnknown || !valid(view) || !target.allFinite()) {
    return std::nullopt;
  }
  Eyes eyes = sensor_eyes(view, target);
  // Outside the sweep: the eyes of its middle profile.
  if (eyes.count == 0) eyes = sweep_eyes(sweep_pose(view, 0.5 * (view.sweep_min + view.sweep_max)));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < eyes.count; ++i) {
    const Eigen::Vector3d d = eyes.at[i] - target;
    if (d.norm() > 1e-9) sum += d.normalized();
  }
  if (!sum.allFinite() || sum.norm() < 1e-9) return std::nullopt;
  return sum.normalized();
}

}  // namespace rangefit::render
