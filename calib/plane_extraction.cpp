#include "calib/plane_extraction.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "detect/common/pca.hpp"

namespace rangefit::calib {
namespace {

using Eigen::Vector3d;

struct Hypothesis {
  Vector3d normal = Vector3d::UnitZ();
  double offset = 0.0;
};

std::vector<std::uint32_t> support(std::span<const Eigen::Vector3d> points,
                                   const std::vector<std::uint32_t>& candidates,
                                   const Hypothesis& h, double tol) {
  std::vector<std::uint32_t> out;
  for (const std::uint32_t i : candidates) {
    if (std::abs(h.normal.dot(points[i]) - h.offset) <= tol) out.push_back(i);
  }
  return out;
}

// Least-squares plane through the inliers, normal turned to `side`.
ExtractedPlane refit(std::span<const Eigen::Vector3d> points, std::vector<std::uint32_t> inliers,
                     const Vector3d& side) {
  ExtractedPlane out;
  std::vector<Vector3d> p;
  p.reserve(inliers.size());
  for (const std::uint32_t i : inliers) p.push_back(points[i]);
  const pca::Plane plane = pca::fit_plane(p);
  if (!plane.valid) return out;
  out.found = true;
  out.normal = plane.normal.dot(side) < 0.0 ? Vector3d(-plane.normal) : plane.normal;
  out.offset_mm = out.normal.dot(plane.point);
  out.rms_mm = plane.rms;
  out.inliers = std::move(inliers);
  return out;
}

// Best plane among the candidates whose normal stays within the cone around `axis`.
ExtractedPlane ransac_plane(std::span<const Eigen::Vector3d> points,
                            const std::vector<std::uint32_t>& candidates, const Vector3d& axis,
                            const PlaneExtractionOptions& o, std::mt19937_64& rng) {
  if (candidates.size() < std::max<std::size_t>(o.min_points, 3)) return {};
  std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
  const double cos_max = std::cos(o.max_normal_angle_rad);
  Hypothesis best;
  std::size_t best_count = 0;
  for (int it = 0; it < o.iterations; ++it) {
    const Vector3d& a = points[candidates[pick(rng)]];
    const Vector3d& b = points[candidates[pick(rng)]];
    const Vector3d& c = points[candidates[pick(rng)]];
    Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9) continue;
    n.normalize();
    if (n.dot(axis) < 0.0) n = -n;
    if (n.dot(axis) < cos_max) continue;
    const Hypothesis h{n, n.dot(a)};
    const std::size_t count = support(points, candidates, h, o.inlier_distance_mm).size();
    if (count > best_count) {
      best_count = count;
      best = h;
    }
  }
  if (best_count < o.min_points) return {};
  ExtractedPlane plane =
      refit(points, support(points, candidates, best, o.inlier_distance_mm), axis);
  if (!plane.found) return plane;
  // Once more with the refitted plane: RANSAC's three points tilt the first support slightly.
  return refit(points,
               support(points, candidates, {plane.normal, plane.offset_mm}, o.inlier_distance_mm),
               axis);
}

}  // namespace

std::array<ExtractedPlane, 6> extract_cube_planes(std::span<const Eigen::Vector3d> points,
                                                  std::span<const Eigen::Vector3d> normals,
                                                  const std::array<CubePlane, 6>& expected,
                                                  const PlaneExtractionOptions& options) {
  std::array<ExtractedPlane, 6> out;
  std::mt19937_64 rng(options.seed);
  const double cos_max = std::cos(options.max_normal_angle_rad);
  for (int a = 0; a < 3; ++a) {
    const Vector3d axis = expected[static_cast<std::size_t>(2 * a)].normal;
    std::vector<std::uint32_t> candidates;
    for (std::size_t i = 0; i < points.size() && i < normals.size(); ++i) {
      if (std::abs(normals[i].dot(axis)) >= cos_max) {
        candidates.push_back(static_cast<std::uint32_t>(i));
      }
    }
    ExtractedPlane first = ransac_plane(points, candidates, axis, options, rng);
    if (!first.found) continue;
    std::vector<std::uint32_t> rest;
    std::set_difference(candidates.begin(), candidates.end(), first.inliers.begin(),
                        first.inliers.end(), std::back_inserter(rest));
    ExtractedPlane second = ransac_plane(points, rest, axis, options, rng);
    // The outer face is the one further along the normal, towards the sensor.
    if (second.found && second.offset_mm > first.offset_mm) std::swap(first, second);
    out[static_cast<std::size_t>(2 * a)] = std::move(first);
    out[static_cast<std::size_t>(2 * a + 1)] = std::move(second);
  }
  return out;
}

}  // namespace rangefit::calib
