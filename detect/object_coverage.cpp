#include "detect/object_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace rangefit {
namespace {

// Where the ray from the part centre along d leaves the part (G = 1), part frame. G is
// homogeneous of degree 2 without taper (G(s d) = s^2 G(d)); with taper it is still increasing
// along the ray (the tapered part is star-shaped about its centre), so bisection finishes it.
Eigen::Vector3d surface_along(const SuperquadricMetric& m, const Eigen::Vector3d& d) {
  const double g = m.value(d);
  if (!(g > 0.0)) return Eigen::Vector3d::Zero();
  double s = 1.0 / std::sqrt(g);
  if (m.model().kx == 0.0 && m.model().ky == 0.0) return s * d;
  double lo = 0.0, hi = s;
  while (m.value(hi * d) < 1.0 && hi < 1e6) hi *= 2.0;
  for (int i = 0; i < 40; ++i) {
    s = 0.5 * (lo + hi);
    (m.value(s * d) < 1.0 ? lo : hi) = s;
  }
  return 0.5 * (lo + hi) * d;
}

}  // namespace

SurfaceCoverage surface_coverage(const Superquadric& sq, const Eigen::Isometry3d& T,
                                 std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                 const CoverageOptions& o) {
  if (!sq.valid() || points.empty() || o.samples < 1) return {};
  const SuperquadricMetric m(sq);
  const double tol = std::max(o.tolerance_mm, o.tolerance_of_min_size * sq.min_size());
  std::vector<std::uint32_t> nbr;
  // Without a viewpoint: the visible side faces the points near the surface.
  Eigen::Vector3d towards = Eigen::Vector3d::Zero();
  if (!o.viewpoint) {
    tree.radius_search(T.translation(), 1.2 * sq.max_size(), nbr);
    const Eigen::Isometry3d inv = T.inverse();
    for (std::uint32_t i : nbr) {
      if (std::abs(m.value(inv * points[i]) - 1.0) < 0.2) towards += points[i] - T.translation();
    }
    if (towards.norm() < 1e-9) return {};
  }
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  int visible = 0, covered = 0, seen_through = 0;
  for (int i = 0; i < o.samples; ++i) {
    // Fibonacci sphere, stretched by the sizes: even in the normalised coordinates.
    const double z = 1.0 - (2.0 * i + 1.0) / o.samples;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    const Eigen::Vector3d d(sq.a1 * r * std::cos(phi), sq.a2 * r * std::sin(phi), sq.a3 * z);
    const Eigen::Vector3d q = surface_along(m, d);
    Eigen::Vector3d grad;
    m.value_and_gradient(q, grad);
    if (grad.squaredNorm() == 0.0) continue;
    const Eigen::Vector3d p = T * q;
    const Eigen::Vector3d n = T.linear() * grad;
    const Eigen::Vector3d view = o.viewpoint ? Eigen::Vector3d(*o.viewpoint - p) : towards;
    if (n.dot(view) <= 0.0) continue;  // faces away: not seen in a single view
    if (o.removed_plane && o.removed_plane->valid &&
        std::abs(o.removed_plane->normal.dot(p - o.removed_plane->point)) <
            o.plane_margin_mm + tol) {
      continue;
    }
    ++visible;
    tree.knn_search(p, 1, nbr);
    if (!nbr.empty() && (points[nbr[0]] - p).norm() <= tol) ++covered;
    // A sample at a silhouette is not seen past by a small pose error: along() looks at the
    // neighbouring pixels too.
    if (o.first_returns && o.first_returns->along(p, tol) == RayEvidence::kBehind) ++seen_through;
  }
  if (visible == 0) return {};
  return {static_cast<double>(covered) / visible, static_cast<double>(seen_through) / visible};
}

}  // namespace rangefit
