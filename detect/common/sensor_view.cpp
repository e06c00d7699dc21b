#include "detect/common/sensor_view.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace rangefit {
namespace {

bool unit(const Eigen::Vector3d& v) { return v.allFinite() && std::abs(v.norm() - 1.0) < 1e-6; }

Eyes two_eyes(const Eigen::Vector3d& apex, const Eigen::Vector3d& camera_offset) {
  Eyes e;
  e.at[0] = apex;
  e.count = 1;
  if (camera_offset.squaredNorm() > 0.0) e.at[e.count++] = apex + camera_offset;
  return e;
}

}  // namespace

bool valid(const SensorView& v) {
  if (!v.origin.allFinite() || !v.camera_offset.allFinite() || !v.pivot.allFinite() ||
      !std::isfinite(v.sweep_min) || !std::isfinite(v.sweep_max)) {
    return false;
  }
  switch (v.kind) {
    case SensorView::Kind::kUnknown:
    case SensorView::Kind::kPoint:
      return true;
    case SensorView::Kind::kLinearSweep:
      return unit(v.direction) && unit(v.plane_normal) && v.sweep_max > v.sweep_min &&
             std::abs(v.plane_normal.dot(v.direction)) > 1e-3;
    case SensorView::Kind::kRotarySweep:
      return unit(v.direction) && unit(v.plane_normal) && v.sweep_max > v.sweep_min &&
             v.sweep_max - v.sweep_min < 2.0 * std::numbers::pi;
  }
  return false;
}

std::optional<double> sweep_position(const SensorView& v, const Eigen::Vector3d& p) {
  switch (v.kind) {
    case SensorView::Kind::kUnknown:
    case SensorView::Kind::kPoint:
      return std::nullopt;
    case SensorView::Kind::kLinearSweep: {
      // The plane through origin + s d with normal n holds p: n.(p - o - s d) = 0.
      const double nd = v.plane_normal.dot(v.direction);
      if (std::abs(nd) < 1e-12) return std::nullopt;
      const double s = v.plane_normal.dot(p - v.origin) / nd;
      if (!(s >= v.sweep_min && s <= v.sweep_max)) return std::nullopt;
      return s;
    }
    case SensorView::Kind::kRotarySweep: {
      // R(t) n . (p - c) = n . (o - c) (a turn keeps dot products). With a the axis:
      // R(t) n = (n.a) a + cos t n_perp + sin t (a x n), so A + B cos t + C sin t = k.
      const Eigen::Vector3d& a = v.direction;
      const Eigen::Vector3d q = p - v.pivot;
      const Eigen::Vector3d n_perp = v.plane_normal - v.plane_normal.dot(a) * a;
      const double A = v.plane_normal.dot(a) * a.dot(q);
      const double B = n_perp.dot(q), C = a.cross(v.plane_normal).dot(q);
      const double k = v.plane_normal.dot(v.origin - v.pivot);
      const double r = std::hypot(B, C);
      if (r < 1e-12 || std::abs(k - A) > r) return std::nullopt;
      const double phi = std::atan2(C, B), delta = std::acos(std::clamp((k - A) / r, -1.0, 1.0));
      const double mid = 0.5 * (v.sweep_min + v.sweep_max);
      double best = 0.0, best_dist = INFINITY;
      for (double t0 : {phi + delta, phi - delta}) {
        // The root nearest the middle of the sweep, in the sweep's own turn.
        const double t =
            t0 + 2.0 * std::numbers::pi * std::round((mid - t0) / (2.0 * std::numbers::pi));
        if (t >= v.sweep_min && t <= v.sweep_max && std::abs(t - mid) < best_dist) {
          best = t;
          best_dist = std::abs(t - mid);
        }
      }
      if (!std::isfinite(best_dist)) return std::nullopt;
      return best;
    }
  }
  return std::nullopt;
}

SweepPose sweep_pose(const SensorView& v, double s) {
  if (v.kind == SensorView::Kind::kRotarySweep) {
    const Eigen::AngleAxisd R(s, v.direction);
    return {v.pivot + R * (v.origin - v.pivot), R * v.plane_normal, R * v.camera_offset};
  }
  return {v.origin + s * v.direction, v.plane_normal, v.camera_offset};
}

Eyes sensor_eyes(const SensorView& v, const Eigen::Vector3d& p) {
  if (v.kind == SensorView::Kind::kPoint) return {1, {v.origin, Eigen::Vector3d::Zero()}};
  const std::optional<double> s = sweep_position(v, p);
  if (!s) return {};
  const SweepPose pose = sweep_pose(v, *s);
  return two_eyes(pose.apex, pose.camera_offset);
}

}  // namespace rangefit
