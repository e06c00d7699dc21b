#include "detect/common/sensor_view.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace rangefit {
namespace {

bool unit(const Eigen::Vector3d& v) { return v.allFinite() && std::abs(v.norm() - 1.0) < 1e-6; }

}  // namespace

bool valid(const SensorView& v) {
  if (!v.origin.allFinite() || !v.camera_offset.allFinite() ||
      !v.second_camera_offset.allFinite() || !v.pivot.allFinite() || !std::isfinite(v.sweep_min) ||
      !std::isfinite(v.sweep_max)) {
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
    return {v.pivot + R * (v.origin - v.pivot), R * v.plane_normal, R * v.camera_offset,
            R * v.second_camera_offset};
  }
  return {v.origin + s * v.direction, v.plane_normal, v.camera_offset, v.second_camera_offset};
}

Eyes sweep_eyes(const SweepPose& pose) {
  Eyes e;
  e.at[0] = pose.apex;
  e.count = 1;
  for (const Eigen::Vector3d& offset : {pose.camera_offset, pose.second_camera_offset}) {
    if (offset.squaredNorm() > 0.0) e.at[static_cast<std::size_t>(e.count++)] = pose.apex + offset;
  }
  return e;
}

std::optional<SensorView> with_second_camera(const SensorView& a, const SensorView& b,
                                             double tolerance_mm, double tolerance_rad) {
  const bool sweep =
      a.kind == SensorView::Kind::kLinearSweep || a.kind == SensorView::Kind::kRotarySweep;
  if (!sweep || b.kind != a.kind || !valid(a) || !valid(b)) return std::nullopt;
  const auto parallel = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    return u.cross(v).norm() <= tolerance_rad && u.dot(v) > 0.0;
  };
  const double range_tolerance =
      a.kind == SensorView::Kind::kLinearSweep ? tolerance_mm : tolerance_rad;
  const bool one_camera_each =
      a.camera_offset.squaredNorm() > 0.0 && b.camera_offset.squaredNorm() > 0.0 &&
      a.second_camera_offset.squaredNorm() == 0.0 && b.second_camera_offset.squaredNorm() == 0.0;
  if (!one_camera_each || !parallel(a.plane_normal, b.plane_normal) ||
      !parallel(a.direction, b.direction) ||
      std::abs(a.plane_normal.dot(b.origin - a.origin)) > tolerance_mm ||
      std::abs(a.sweep_min - b.sweep_min) > range_tolerance ||
      std::abs(a.sweep_max - b.sweep_max) > range_tolerance) {
    return std::nullopt;
  }
  if (a.kind == SensorView::Kind::kRotarySweep && (a.pivot - b.pivot).norm() > tolerance_mm) {
    return std::nullopt;
  }
  SensorView out = a;
  out.second_camera_offset = b.origin + b.camera_offset - a.origin;
  // The same camera twice (one device's two sweeps) is not a second camera.
  if ((out.second_camera_offset - a.camera_offset).norm() <= tolerance_mm) return std::nullopt;
  return out;
}

Eyes sensor_eyes(const SensorView& v, const Eigen::Vector3d& p) {
  if (v.kind == SensorView::Kind::kPoint) {
    Eyes e;
    e.count = 1;
    e.at[0] = v.origin;
    return e;
  }
  const std::optional<double> s = sweep_position(v, p);
  if (!s) return {};
  return sweep_eyes(sweep_pose(v, *s));
}

}  // namespace rangefit
