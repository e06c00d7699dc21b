#include "detect/cylinder_rsf.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include "detect/pca.hpp"

namespace rangefit {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Eq. 4.7-4.9: mean of cross products of normal pairs with 15 deg < gamma < 75 deg, each flipped
// into the prior axis's hemisphere.
Eigen::Vector3d axis_from_pairs(std::span<const Eigen::Vector3d> normals,
                                const Eigen::Vector3d& prior, const RsfOptions& o,
                                std::mt19937_64& rng, int& accepted) {
  std::uniform_int_distribution<std::size_t> pick(0, normals.size() - 1);
  // sin(gamma) bounds, tested on |n_i x n_j| = sin(gamma) plus the sign of cos(gamma).
  const double cos_lo = std::cos(o.min_pair_angle_deg * kDeg);
  const double cos_hi = std::cos(o.max_pair_angle_deg * kDeg);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  accepted = 0;
  const long max_draws = static_cast<long>(o.axis_samples) * o.max_draws_per_sample;
  for (long d = 0; d < max_draws && accepted < o.axis_samples; ++d) {
    const Eigen::Vector3d& a = normals[pick(rng)];
    const Eigen::Vector3d& b = normals[pick(rng)];
    const double c = a.dot(b);
    if (c >= cos_lo || c <= cos_hi) continue;
    Eigen::Vector3d o_k = a.cross(b).normalized();
    if (o_k.dot(prior) < 0.0) o_k = -o_k;
    sum += o_k;
    ++accepted;
  }
  return accepted > 0 ? Eigen::Vector3d(sum.normalized()) : prior;
}

// Eq. 4.11: circumradius of one projected triangle, or 0 when its area is at most min_area
// (eq. 4.14). Twice the area from the cross product equals Heron's formula (eq. 4.13).
double circumradius(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    double min_area) {
  const Eigen::Vector2d ab = b - a, ac = c - a;
  const double area = 0.5 * std::abs(ab.x() * ac.y() - ab.y() * ac.x());
  if (area <= min_area) return 0.0;
  return ab.norm() * ac.norm() * (c - b).norm() / (4.0 * area);
}

double estimate(std::vector<double>& radii, const RsfOptions& o) {
  std::sort(radii.begin(), radii.end());
  const std::size_t n = radii.size();
  std::size_t cut = 0;  // kMean: the thesis's eq. 4.15
  if (o.radius_estimator == RadiusEstimator::kMedian) {
    return n % 2 ? radii[n / 2] : 0.5 * (radii[n / 2 - 1] + radii[n / 2]);
  }
  if (o.radius_estimator == RadiusEstimator::kTrimmedMean) {
    cut = static_cast<std::size_t>(std::clamp(o.trim_fraction, 0.0, 0.49) * static_cast<double>(n));
  }
  double s = 0.0;
  for (std::size_t i = cut; i < n - cut; ++i) s += radii[i];
  return s / static_cast<double>(n - 2 * cut);
}

// Eq. 4.11-4.15: radius from random wall triangles projected on the plane normal to u.
double radius_from_triangles(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& u,
                             const Eigen::Vector3d& centre, double expected_radius,
                             const RsfOptions& o, std::mt19937_64& rng, int& accepted) {
  const Eigen::Vector3d e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  const std::size_t n = points.size();
  std::vector<Eigen::Vector2d> q(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = points[i] - centre;
    q[i] = {d.dot(e1), d.dot(e2)};
  }
  if (o.stratified_triangles) {
    // Beyond the thesis: order the points by azimuth about the prior axis and draw one vertex
    // from each third of the arc, so most triangles are wide enough for eq. 4.14 even on a
    // 120-degree fragment (where uniform draws almost never are).
    const Eigen::Vector2d mean =
        std::accumulate(q.begin(), q.end(), Eigen::Vector2d(0, 0)) / static_cast<double>(n);
    const double ref = std::atan2(mean.y(), mean.x());
    std::vector<std::pair<double, std::size_t>> az(n);
    for (std::size_t i = 0; i < n; ++i) {
      az[i] = {std::remainder(std::atan2(q[i].y(), q[i].x()) - ref, 2.0 * std::numbers::pi), i};
    }
    std::sort(az.begin(), az.end());
    std::vector<Eigen::Vector2d> sorted(n);
    for (std::size_t i = 0; i < n; ++i) sorted[i] = q[az[i].second];
    q.swap(sorted);
  }
  const std::size_t third = std::max<std::size_t>(n / 3, 1);
  std::uniform_int_distribution<std::size_t> pick_all(0, n - 1), pick_third(0, third - 1);
  auto draw = [&](int k) -> const Eigen::Vector2d& {
    if (!o.stratified_triangles || n < 3) return q[pick_all(rng)];
    return q[std::min(n - 1, k * third + pick_third(rng))];
  };
  double min_area = o.min_area_factor * std::numbers::pi * expected_radius * expected_radius;
  std::vector<double> radii;
  radii.reserve(static_cast<std::size_t>(o.radius_samples));
  const long max_draws = static_cast<long>(o.radius_samples) * o.max_draws_per_sample;
  long draws = 0;
  for (int pass = 0; pass < 8 && static_cast<int>(radii.size()) < o.radius_samples; ++pass) {
    // A fragment too narrow for the thesis's area limit: halve the limit and draw again.
    const long pass_end = draws + max_draws / 8;
    for (; draws < pass_end && static_cast<int>(radii.size()) < o.radius_samples; ++draws) {
      const double r = circumradius(draw(0), draw(1), draw(2), min_area);
      if (r > 0.0) radii.push_back(r);
    }
    if (static_cast<int>(radii.size()) * 4 >= o.radius_samples) break;
    radii.clear();
    min_area *= 0.5;
  }
  accepted = static_cast<int>(radii.size());
  return radii.empty() ? 0.0 : estimate(radii, o);
}

}  // namespace

double axis_distance(const Cylinder& c, const Eigen::Vector3d& p) {
  return c.axis.cross(c.point - p).norm();  // eq. 4.16 with a unit axis
}

const char* to_string(RsfStatus s) {
  switch (s) {
    case RsfStatus::kOk:
      return "ok";
    case RsfStatus::kTooFewPoints:
      return "too few wall points for a cylinder fit";
    case RsfStatus::kNoAxisPairs:
      return "no wall-normal pair within the pair-angle limits";
    case RsfStatus::kNoTriangles:
      return "no wall triangle above the minimum area";
    case RsfStatus::kDegenerateAxis:
      return "axis points do not define a line";
  }
  return "unknown";
}

RsfResult fit_cylinder_rsf(std::span<const Eigen::Vector3d> points,
                           std::span<const Eigen::Vector3d> normals,
                           const Eigen::Vector3d& prior_axis, const Eigen::Vector3d& prior_point,
                           double expected_radius, const RsfOptions& o, std::uint64_t seed) {
  RsfResult res;
  if (points.size() < 3 || normals.size() != points.size() || !(expected_radius > 0.0)) {
    return res;
  }
  std::mt19937_64 rng(seed);
  const Eigen::Vector3d prior = prior_axis.normalized();
  const Eigen::Vector3d u = axis_from_pairs(normals, prior, o, rng, res.axis_pairs);
  res.axis_from_pairs = u;
  if (res.axis_pairs == 0) {
    res.status = RsfStatus::kNoAxisPairs;
    return res;
  }
  const double r =
      radius_from_triangles(points, u, prior_point, expected_radius, o, rng, res.triangles);
  if (res.triangles == 0 || !(r > 0.0)) {
    res.status = RsfStatus::kNoTriangles;
    return res;
  }
  // Axis points: every wall normal crosses the axis at distance r from its point.
  std::vector<Eigen::Vector3d> axis_pts(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) axis_pts[i] = points[i] + r * normals[i];
  if (o.cluster_axis_points) {
    // Mean shift in the plane normal to u, seeded on the prior axis: keeps only the axis points
    // of this bore (a neighbour's land on its own axis, an outer wall's 2 r away).
    const double window = std::max(o.cluster_window_factor * r, 0.2);
    Eigen::Vector3d centre = prior_point;
    std::vector<Eigen::Vector3d> kept;
    for (int it = 0; it < 10; ++it) {
      kept.clear();
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const auto& a : axis_pts) {
        const Eigen::Vector3d d = a - centre;
        if ((d - d.dot(u) * u).norm() < window) {
          kept.push_back(a);
          sum += a;
        }
      }
      if (kept.empty()) break;
      const Eigen::Vector3d next = sum / static_cast<double>(kept.size());
      const Eigen::Vector3d step = next - centre;
      centre = next;
      if ((step - step.dot(u) * u).norm() < 1e-4) break;
    }
    if (kept.size() >= 3) axis_pts.swap(kept);
  }
  res.axis_points_used = static_cast<int>(axis_pts.size());
  const pca::Line line = pca::fit_line(axis_pts);
  if (!line.valid) {
    res.status = RsfStatus::kDegenerateAxis;
    return res;
  }
  // A short wall fragment gives a stubby cloud of axis points whose main direction is noise;
  // then the pair estimate u is the better axis.
  const pca::Eigen3 e = pca::eigen_symmetric(pca::covariance(axis_pts, line.point));
  Eigen::Vector3d v = e.values(2) > 4.0 * e.values(1) ? line.direction : u;
  if (v.dot(prior) < 0.0) v = -v;
  res.cylinder = {line.point, v, r};
  res.status = RsfStatus::kOk;
  return res;
}

}  // namespace rangefit
