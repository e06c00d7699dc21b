#include "render/sensor_direction.hpp"

#include <Eigen/Geometry>

namespace rangefit::render {
namespace {

// The eyes of the profile in the middle of the sweep (as sensor_eyes places them).
Eyes mid_sweep_eyes(const SensorView& v) {
  const double s = 0.5 * (v.sweep_min + v.sweep_max);
  Eyes e;
  if (v.kind == SensorView::Kind::kLinearSweep) {
    e.at[0] = v.origin + s * v.direction;
    e.at[1] = e.at[0] + v.camera_offset;
  } else {
    const Eigen::AngleAxisd R(s, v.direction);
    e.at[0] = v.pivot + R * (v.origin - v.pivot);
    e.at[1] = e.at[0] + R * v.camera_offset;
  }
  e.count = v.camera_offset.squaredNorm() > 0.0 ? 2 : 1;
  return e;
}

}  // namespace

std::optional<Eigen::Vector3d> toward_scan_sensor(const SensorView& view,
                                                  const Eigen::Vector3d& target) {
  if (view.kind == SensorView::Kind::kUnknown || !valid(view) || !target.allFinite()) {
    return std::nullopt;
  }
  Eyes eyes = sensor_eyes(view, target);
  if (eyes.count == 0) eyes = mid_sweep_eyes(view);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < eyes.count; ++i) {
    const Eigen::Vector3d d = eyes.at[i] - target;
    if (d.norm() > 1e-9) sum += d.normalized();
  }
  if (!sum.allFinite() || sum.norm() < 1e-9) return std::nullopt;
  return sum.normalized();
}

}  // namespace rangefit::render
