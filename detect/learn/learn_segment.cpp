#include "detect/learn/learn_segment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <utility>

#include "detect/common/kdtree.hpp"

namespace rangefit {
namespace {

// The sample spacing of the scan: over an even sample of at most 500 points, the median of the
// distance to the nearest other point and of the spacing the 16 nearest imply (radius r of 16
// points: pi r^2 / 16 of surface each), the larger. A laser-stripe scan is far denser along its
// lines than across them (a steep face seen at a low angle: lines 1 mm apart, points 0.1 mm
// along them); the nearest neighbour alone measures the along-line spacing, and a gap a few
// times that cuts the object into its lines.
double median_spacing(std::span<const Eigen::Vector3d> pts, const KdTree& tree) {
  constexpr int kArea = 16;
  std::vector<double> d, a;
  std::vector<std::uint32_t> nn;
  const std::size_t stride = std::max<std::size_t>(1, pts.size() / 500);
  for (std::size_t i = 0; i < pts.size(); i += stride) {
    tree.knn_search(pts[i], kArea + 1, nn);
    if (nn.size() >= 2) d.push_back((pts[nn[1]] - pts[i]).norm());
    if (nn.size() == kArea + 1) {
      a.push_back((pts[nn[kArea]] - pts[i]).norm() * std::sqrt(std::numbers::pi / kArea));
    }
  }
  if (d.empty()) return 1.0;
  const auto median = [](std::vector<double>& v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  return std::max(median(d), median(a));
}

}  // namespace

SegmentResult segment_object(std::span<const Eigen::Vector3d> points,
                             const SegmentOptions& options) {
  SegmentResult out;
  std::vector<std::uint32_t> rest;
  if (options.remove_plane) {
    // The plane removal draws its patches and seeds at even strides through the points; an
    // organised scan (a stripe ranger's profiles, row by row) aliases with those strides, so the
    // seeds fall on a few lines across the table and a vertical plane through one of them (a face
    // of the object) can outvote the table. The points are handed over in a seeded shuffle.
    std::vector<std::uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::mt19937_64 rng(options.plane.seed);
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<Eigen::Vector3d> shuffled;
    shuffled.reserve(points.size());
    for (std::uint32_t i : order) shuffled.push_back(points[i]);
    out.plane = remove_dominant_plane(shuffled, options.plane);
    for (std::uint32_t& i : out.plane.remaining) i = order[i];
    std::sort(out.plane.remaining.begin(), out.plane.remaining.end());
    rest = out.plane.remaining;
  } else {
    rest.resize(points.size());
    std::iota(rest.begin(), rest.end(), 0u);
  }
  if (rest.size() < std::max<std::size_t>(options.min_points, 2)) return out;
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(rest.size());
  for (std::uint32_t i : rest) pts.push_back(points[i]);
  const KdTree tree(pts);
  out.gap_mm =
      options.gap_mm > 0.0 ? options.gap_mm : std::max(4.0 * median_spacing(pts, tree), 0.01);
  // Flood fill over the radius graph.
  std::vector<int> label(pts.size(), -1);
  std::vector<std::uint32_t> queue, near;
  std::vector<std::pair<double, std::vector<std::uint32_t>>> found;  // score, cluster
  int next = 0;
  for (std::size_t s = 0; s < pts.size(); ++s) {
    if (label[s] >= 0) continue;
    queue.assign(1, static_cast<std::uint32_t>(s));
    label[s] = next;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      tree.radius_search(pts[queue[q]], out.gap_mm, near);
      for (std::uint32_t j : near) {
        if (label[j] < 0) {
          label[j] = next;
          queue.push_back(j);
        }
      }
    }
    ++next;
    if (queue.size() < options.min_points) continue;
    ++out.clusters;
    double score = -static_cast<double>(queue.size());
    if (options.near) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (std::uint32_t j : queue) c += pts[j];
      score = (c / static_cast<double>(queue.size()) - *options.near).norm();
    }
    found.emplace_back(score, queue);
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  const std::size_t keep = std::min<std::size_t>(found.size(), std::max(options.keep, 1));
  for (std::size_t k = 0; k < keep; ++k) {
    std::vector<std::uint32_t> cluster;
    for (std::uint32_t j : found[k].second) cluster.push_back(rest[j]);
    std::sort(cluster.begin(), cluster.end());
    out.object.insert(out.object.end(), cluster.begin(), cluster.end());
    out.kept.push_back(std::move(cluster));
  }
  std::sort(out.object.begin(), out.object.end());
  return out;
}

}  // namespace rangefit
