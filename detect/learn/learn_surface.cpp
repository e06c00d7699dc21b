#include "detect/learn/learn_surface.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "detect/common/kdtree.hpp"

namespace rangefit {

double radial_rms_mm(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                     std::span<const Eigen::Vector3d> points) {
  if (points.empty()) return 0.0;
  const SuperquadricMetric m(sq);
  const Eigen::Isometry3d inv = T_world_part.inverse();
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = inv * p;
    const double g = m.value(q);
    const double d = g > 0.0 ? q.norm() * std::abs(1.0 - 1.0 / std::sqrt(g)) : 0.0;
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
