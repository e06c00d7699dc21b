#include "sim/superquadric_raycast.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace rangefit::sim {
namespace {

constexpr int kCoarseSamples = 48;  // samples of the gauge along the ray inside the bounds
constexpr int kMaxRootSteps = 100;

// Slab test of the ray against the part bounds; false when it misses [t_lo, t_hi].
bool clip_to_bounds(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& o,
                    const Eigen::Vector3d& d, double& t_lo, double& t_hi) {
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-300) {
      if (o[i] < box.min()[i] || o[i] > box.max()[i]) return false;
      continue;
    }
    double ta = (box.min()[i] - o[i]) / d[i];
    double tb = (box.max()[i] - o[i]) / d[i];
    if (ta > tb) std::swap(ta, tb);
    t_lo = std::max(t_lo, ta);
    t_hi = std::min(t_hi, tb);
    if (t_lo > t_hi) return false;
  }
  return true;
}

}  // namespace

std::optional<double> intersect_superquadric(const Superquadric& sq,
                                             const Eigen::Isometry3d& T_world_part,
                                             const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& dir, double t_max,
                                             double t_min) {
  if (!sq.valid() || !origin.allFinite() || !dir.allFinite() || dir.squaredNorm() == 0.0 ||
      std::isnan(t_max) || std::isnan(t_min) || !(t_max > t_min)) {
    return std::nullopt;
  }
  const Eigen::Isometry3d T_part_world = T_world_part.inverse();
  const Eigen::Vector3d o = T_part_world * origin;
  const Eigen::Vector3d d = T_part_world.linear() * dir;
  Eigen::AlignedBox3d box = part_bounds(sq);
  const double pad = 1e-6 * sq.max_size();
  box.min().array() -= pad;
  box.max().array() += pad;
  double lo = t_min;
  double hi = std::isfinite(t_max) ? t_max : std::numeric_limits<double>::max();
  if (!clip_to_bounds(box, o, d, lo, hi)) return std::nullopt;
  const SuperquadricMetric sqm(sq);
  const auto g = [&](double t) { return sqm.value(o + t * d); };
  if (g(lo) <= 1.0) {
    // Starts inside: a ray leaving the part does not hit it from outside.
    if (lo > t_min) return lo;
    return std::nullopt;
  }
  // G^(1/2) is a gauge (convex along a ray) for the untapered part, so the inside is one interval;
  // sampling finds the first inside sample, else a golden-section search around the smallest one
  // catches grazing hits between samples.
  double inside_t = std::numeric_limits<double>::quiet_NaN();
  double prev_t = lo;
  double best_t = lo, best_g = g(lo);
  const double step = (hi - lo) / kCoarseSamples;
  for (int i = 1; i <= kCoarseSamples; ++i) {
    const double t = lo + step * i;
    const double gt = g(t);
    if (gt <= 1.0) {
      inside_t = t;
      break;
    }
    if (gt < best_g) best_g = gt, best_t = t;
    prev_t = t;
  }
  if (std::isnan(inside_t)) {
    double a = std::max(lo, best_t - step), b = std::min(hi, best_t + step);
    const double r = (std::sqrt(5.0) - 1.0) / 2.0;
    double c = b - r * (b - a), e = a + r * (b - a);
    double gc = g(c), ge = g(e);
    for (int i = 0; i < 60 && gc > 1.0 && ge > 1.0; ++i) {
      if (gc < ge) {
        b = e, e = c, ge = gc, c = b - r * (b - a), gc = g(c);
      } else {
        a = c, c = e, gc = ge, e = a + r * (b - a), ge = g(e);
      }
    }
    if (gc <= 1.0) {
      inside_t = c;
    } else if (ge <= 1.0) {
      inside_t = e;
    } else {
      return std::nullopt;
    }
    prev_t = lo;
    // The first entry lies before the inside point; bracket from the start of the bounds.
    for (double t = inside_t - step; t > lo; t -= step) {
      if (g(t) > 1.0) {
        prev_t = t;
        break;
      }
    }
  }
  // Safeguarded Newton on G - 1 inside the bracket [out, in].
  double t_out = prev_t, t_in = inside_t;
  double t = 0.5 * (t_out + t_in);
  const double dir_norm = d.norm();
  for (int i = 0; i < kMaxRootSteps && (t_in - t_out) * dir_norm > 1e-9; ++i) {
    Eigen::Vector3d grad;
    const double gt = sqm.value_and_gradient(o + t * d, grad) - 1.0;
    if (gt > 0.0) {
      t_out = t;
    } else {
      t_in = t;
    }
    const double slope = grad.dot(d);
    double next = slope != 0.0 ? t - gt / slope : 0.5 * (t_out + t_in);
    if (!(next > t_out && next < t_in)) next = 0.5 * (t_out + t_in);
    if (std::abs(next - t) * dir_norm < 1e-10) {
      t = next;
      break;
    }
    t = next;
  }
  if (t <= t_min || t > t_max) return std::nullopt;
  return t;
}

Eigen::Vector3d superquadric_normal(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                                    const Eigen::Vector3d& p_world) {
  Eigen::Vector3d grad;
  metric_and_gradient(sq, T_world_part.inverse() * p_world, grad);
  const Eigen::Vector3d n = T_world_part.linear() * grad;
  const double len = n.norm();
  return len > 0.0 && std::isfinite(len) ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
}

RenderedScene render_scene(const std::vector<ScenePart>& parts, const SceneView& view) {
  RenderedScene out;
  if (view.width <= 0 || view.height <= 0) return out;
  const Eigen::Vector3d fwd = (view.target - view.eye).normalized();
  Eigen::Vector3d right = fwd.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-9) right = Eigen::Vector3d::UnitX();
  right.normalize();
  const Eigen::Vector3d up = right.cross(fwd);
  const double half_w = std::tan(0.5 * view.fov_deg * std::numbers::pi / 180.0);
  const double half_h = half_w * view.height / view.width;
  std::mt19937_64 rng(view.noise_seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  out.cloud.grid.rows = view.height;
  out.cloud.grid.cols = view.width;
  out.cloud.grid.index.assign(static_cast<std::size_t>(view.width) * view.height, -1);
  for (int r = 0; r < view.height; ++r) {
    for (int c = 0; c < view.width; ++c) {
      const double sx = (2.0 * (c + 0.5) / view.width - 1.0) * half_w;
      const double sy = (1.0 - 2.0 * (r + 0.5) / view.height) * half_h;
      const Eigen::Vector3d dir = (fwd + sx * right + sy * up).normalized();
      double best = std::numeric_limits<double>::infinity();
      std::int32_t label = -2;
      if (view.table && dir.z() < 0.0) {
        const double t = (view.table_z - view.eye.z()) / dir.z();
        const Eigen::Vector3d p = view.eye + t * dir;
        if (t > 0.0 && p.x() >= view.table_min.x() && p.x() <= view.table_max.x() &&
            p.y() >= view.table_min.y() && p.y() <= view.table_max.y()) {
          best = t, label = -1;
        }
      }
      for (std::size_t i = 0; i < parts.size(); ++i) {
        const auto t =
            intersect_superquadric(parts[i].model, parts[i].T_world_part, view.eye, dir, best);
        if (t && *t < best) best = *t, label = static_cast<std::int32_t>(i);
      }
      if (label == -2) continue;
      Eigen::Vector3d p = view.eye + best * dir;
      if (view.noise_sigma_mm > 0.0) {
        // One draw per statement, z first: a seed makes the same scan whatever order a compiler
        // evaluates a call's arguments in (z, y, x is the order the recorded scans were made in).
        const double nz = noise(rng), ny = noise(rng), nx = noise(rng);
        p += view.noise_sigma_mm * Eigen::Vector3d(nx, ny, nz);
      }
      out.cloud.grid.index[static_cast<std::size_t>(r) * view.width + c] =
          static_cast<std::int32_t>(out.cloud.points.size());
      out.cloud.points.push_back(p);
      out.label.push_back(label);
    }
  }
  return out;
}

}  // namespace rangefit::sim
