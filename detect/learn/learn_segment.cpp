#include "detect/learn/learn_segment.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

#include "detect/common/kdtree.hpp"

namespace rangefit {
namespace {

// Median distance to the nearest other point over an even sample of at most 500 points.
double median_spacing(std::span<const Eigen::Vector3d> pts, const KdTree& tree) {
  std::vector<double> d;
  std::vector<std::uint32_t> nn;
  const std::size_t stride = std::max<std::size_t>(1, pts.size() / 500);
  for (std::size_t i = 0; i < pts.size(); i += stride) {
    tree.knn_search(pts[i], 2, nn);
    if (nn.size() == 2) d.push_back((pts[nn[1]] - pts[i]).norm());
  }
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

}  // namespace

SegmentResult segment_object(std::span<const Eigen::Vector3d> points,
                             const SegmentOptions& options) {
  SegmentResult out;
  std::vector<std::uint32_t> rest;
  if (options.remove_plane) {
    out.plane = remove_dominant_plane(points, options.plane);
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
