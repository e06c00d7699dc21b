#include "detect/common/plane_removal.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "detect/common/parallel_for.hpp"

namespace rangefit {
namespace {

std::vector<std::uint32_t> all_indices(std::size_t n) {
  std::vector<std::uint32_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0u);
  return idx;
}

// Radically reduced resolution: an even spread of the cloud, with a seeded offset.
std::vector<Eigen::Vector3d> even_spread(std::span<const Eigen::Vector3d> points,
                                         std::size_t sub_n, std::uint64_t seed) {
  const std::size_t n = points.size();
  std::vector<Eigen::Vector3d> sub(sub_n);
  const double stride = static_cast<double>(n) / static_cast<double>(sub_n);
  const double offset = static_cast<double>(seed % 997) / 997.0 * stride;
  for (std::size_t i = 0; i < sub_n; ++i) {
    sub[i] =
        points[std::min(n - 1, static_cast<std::size_t>(offset + stride * static_cast<double>(i)))];
  }
  return sub;
}

// A seed's PCA plane patch and how many seeds it supports (within tolerance), with the median
// distance of those.
struct SeedPlane {
  pca::Plane plane;
  std::size_t support = 0;
  double median = 0.0;
};

// One PCA plane patch of k points per seed, verified against the other seeds (most within
// tolerance wins, the smaller median distance of the supporters breaks ties; the first seed of
// equals). Invalid when no patch gives a plane. The seeds are tried on `threads` threads, each
// into its own slot.
pca::Plane best_seed_plane(std::span<const Eigen::Vector3d> sub, std::size_t seeds, std::size_t k,
                           double tol, int threads) {
  const std::size_t sub_n = sub.size();
  std::vector<std::size_t> seed_idx(seeds);
  for (std::size_t s = 0; s < seeds; ++s) seed_idx[s] = s * sub_n / seeds;
  std::vector<SeedPlane> tried(seeds);
  parallel_for(seeds, threads, [&](std::size_t s) {
    std::vector<std::pair<double, std::size_t>> dist(sub_n);
    const Eigen::Vector3d& c = sub[seed_idx[s]];
    for (std::size_t i = 0; i < sub_n; ++i) dist[i] = {(sub[i] - c).squaredNorm(), i};
    std::nth_element(dist.begin(), dist.begin() + static_cast<std::ptrdiff_t>(k - 1), dist.end());
    std::vector<Eigen::Vector3d> patch(k);
    for (std::size_t i = 0; i < k; ++i) patch[i] = sub[dist[i].second];
    const pca::Plane plane = pca::fit_plane(patch);
    if (!plane.valid) return;
    std::vector<double> support;
    for (std::size_t t = 0; t < seeds; ++t) {
      const double d = std::abs(plane.normal.dot(sub[seed_idx[t]] - plane.point));
      if (d <= tol) support.push_back(d);
    }
    if (support.empty()) return;
    std::nth_element(support.begin(),
                     support.begin() + static_cast<std::ptrdiff_t>(support.size() / 2),
                     support.end());
    tried[s] = {plane, support.size(), support[support.size() / 2]};
  });
  pca::Plane best;
  std::size_t best_support = 0;
  double best_median = 0.0;
  for (const SeedPlane& t : tried) {
    if (t.support == 0) continue;
    if (t.support > best_support || (t.support == best_support && t.median < best_median)) {
      best_support = t.support;
      best_median = t.median;
      best = t.plane;
    }
  }
  return best;
}

}  // namespace

PlaneRemovalResult remove_dominant_plane(std::span<const Eigen::Vector3d> points,
                                         const PlaneRemovalOptions& options) {
  PlaneRemovalResult result;
  const std::size_t n = points.size();
  const std::size_t k = static_cast<std::size_t>(std::max(options.patch_points, 3));
  if (n < k || options.seeds < 1) {
    result.remaining = all_indices(n);
    return result;
  }
  const std::size_t sub_n = std::min(n, std::max(options.subsample, k));
  const std::vector<Eigen::Vector3d> sub = even_spread(points, sub_n, options.seed);
  const double tol = options.distance_tolerance_mm;
  result.plane = best_seed_plane(sub, std::min(sub_n, static_cast<std::size_t>(options.seeds)), k,
                                 tol, options.threads);
  if (!result.plane.valid) {
    result.reason = PlaneRemovalReason::kNotDominant;
    result.remaining = all_indices(n);
    return result;
  }
  // Total least-squares refit on all subsample points of the winning plane.
  std::vector<Eigen::Vector3d> inliers;
  for (const Eigen::Vector3d& p : sub) {
    if (std::abs(result.plane.normal.dot(p - result.plane.point)) <= tol) inliers.push_back(p);
  }
  const pca::Plane refined = pca::fit_plane(inliers);
  if (refined.valid) result.plane = refined;
  // Noisy scans: the tolerance grows with the plane's own noise (its rms), so the table's
  // stragglers beyond 2 mm do not stay behind as thousands of stray points for the object search
  // to seed on (at sigma 0.8 mm a 2 mm band leaves ~1 % of the table).
  const double removal_tol = std::max(tol, options.noise_factor * result.plane.rms);

  std::vector<std::uint32_t> kept;
  kept.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(result.plane.normal.dot(points[i] - result.plane.point)) > removal_tol) {
      kept.push_back(static_cast<std::uint32_t>(i));
    }
  }
  result.plane_points = n - kept.size();
  if (result.plane_points > kept.size()) {
    result.reason = PlaneRemovalReason::kRemoved;
    result.remaining = std::move(kept);
  } else {
    result.reason = PlaneRemovalReason::kNotDominant;
    result.remaining = all_indices(n);
  }
  return result;
}

}  // namespace rangefit
