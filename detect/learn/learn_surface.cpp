#include "detect/learn/learn_surface.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "detect/common/kdtree.hpp"

namespace rangefit {

double RadialDistance::normalising() const {
  // |df/dq| is 1 along the ray on an untapered part and larger elsewhere; the floor only keeps
  // a degenerate gradient (the centre of a part) finite.
  constexpr double kMinGradient = 1e-9;
  return 1.0 / std::max(df_dq.norm(), kMinGradient);
}

namespace {
// The centre itself (G = 0) is inside by about its distance to the surface.
constexpr double kTinyG = 1e-12;
}  // namespace

double radial_distance(double g, double q_norm) {
  return q_norm * (1.0 - 1.0 / std::sqrt(std::max(g, kTinyG)));
}

RadialDistance radial_distance(double g, const Eigen::Vector3d& dg_dq, const Eigen::Vector3d& q) {
  // df/dq = (1 - G^-1/2) q / |q| + |q| G^-3/2 dG/dq / 2.
  const double gs = std::max(g, kTinyG), inv_sqrt = 1.0 / std::sqrt(gs), qn = q.norm();
  RadialDistance r;
  r.f = radial_distance(g, qn);
  r.df_dq = 0.5 * qn * inv_sqrt / gs * dg_dq;
  if (qn > 0.0) r.df_dq += (1.0 - inv_sqrt) / qn * q;
  return r;
}

double radial_surface_distance(const SuperquadricMetric& metric, const Eigen::Vector3d& q) {
  Eigen::Vector3d grad;
  const double g = metric.value_and_gradient(q, grad);
  const RadialDistance r = radial_distance(g, grad, q);
  return r.f * r.normalising();
}

double surface_rms_mm(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                      std::span<const Eigen::Vector3d> points) {
  if (points.empty()) return 0.0;
  const SuperquadricMetric m(sq);
  const Eigen::Isometry3d inv = T_world_part.inverse();
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const double d = radial_surface_distance(m, inv * p);
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(points.size()));
}

double visible_share(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                     std::span<const Eigen::Vector3d> points, double tolerance_mm) {
  if (points.empty()) return 0.0;
  constexpr int kLat = 48, kLon = 96;
  const double pi = std::numbers::pi;
  // Corner points of the grid, then per cell its centre and area (half the cross product of
  // the diagonals of the quad).
  std::vector<Eigen::Vector3d> corner((kLat + 1) * (kLon + 1));
  for (int i = 0; i <= kLat; ++i) {
    for (int j = 0; j <= kLon; ++j) {
      corner[i * (kLon + 1) + j] =
          surface_point(sq, -pi / 2 + pi * i / kLat, -pi + 2 * pi * j / kLon);
    }
  }
  const KdTree tree(points);
  const Eigen::Isometry3d& T = T_world_part;
  double total = 0.0, seen = 0.0;
  std::vector<std::uint32_t> nn;
  for (int i = 0; i < kLat; ++i) {
    for (int j = 0; j < kLon; ++j) {
      const Eigen::Vector3d& p00 = corner[i * (kLon + 1) + j];
      const Eigen::Vector3d& p01 = corner[i * (kLon + 1) + j + 1];
      const Eigen::Vector3d& p10 = corner[(i + 1) * (kLon + 1) + j];
      const Eigen::Vector3d& p11 = corner[(i + 1) * (kLon + 1) + j + 1];
      const double area = 0.5 * (p11 - p00).cross(p10 - p01).norm();
      if (!(area > 0.0)) continue;
      total += area;
      const Eigen::Vector3d mid =
          surface_point(sq, -pi / 2 + pi * (i + 0.5) / kLat, -pi + 2 * pi * (j + 0.5) / kLon);
      tree.knn_search(T * mid, 1, nn);
      if (!nn.empty() && (points[nn[0]] - T * mid).norm() <= tolerance_mm) seen += area;
    }
  }
  return total > 0.0 ? seen / total : 0.0;
}

}  // namespace rangefit
