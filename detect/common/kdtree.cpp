#include "detect/common/kdtree.hpp"

#include <algorithm>
#include <nanoflann.hpp>

namespace rangefit {
namespace {

// nanoflann's dataset adaptor over a span of points.
struct SpanAdaptor {
  std::span<const Eigen::Vector3d> pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return pts[i][static_cast<int>(dim)];
  }
  template <class Bbox>
  bool kdtree_get_bbox(Bbox&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SpanAdaptor>,
                                                 SpanAdaptor, 3, std::uint32_t>;

}  // namespace

struct KdTree::Impl {
  SpanAdaptor adaptor;
  Tree tree;
  explicit Impl(std::span<const Eigen::Vector3d> points)
      : adaptor{points}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

KdTree::KdTree(std::span<const Eigen::Vector3d> points) : impl_(std::make_unique<Impl>(points)) {}
KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

std::size_t KdTree::size() const { return impl_->adaptor.pts.size(); }

void KdTree::radius_search(const Eigen::Vector3d& query, double radius,
                           std::vector<std::uint32_t>& out) const {
  out.clear();
  if (size() == 0) return;
  std::vector<std::pair<std::uint32_t, double>> matches;
  nanoflann::SearchParams params;
  params.sorted = false;
  impl_->tree.radiusSearch(query.data(), radius * radius, matches, params);
  out.reserve(matches.size());
  for (const auto& m : matches) out.push_back(m.first);
}

void KdTree::knn_search(const Eigen::Vector3d& query, std::size_t k,
                        std::vector<std::uint32_t>& out) const {
  out.clear();
  k = std::min(k, size());
  if (k == 0) return;
  out.resize(k);
  std::vector<double> dist2(k);
  const std::size_t found = impl_->tree.knnSearch(query.data(), k, out.data(), dist2.data());
  out.resize(found);
}

std::optional<double> median_neighbour_distance(std::span<const Eigen::Vector3d> points,
                                                const KdTree& tree,
                                                std::span<const std::uint32_t> which) {
  std::vector<double> d;
  std::vector<std::uint32_t> nn;
  for (std::uint32_t i : which) {
    tree.knn_search(points[i], 2, nn);
    if (nn.size() == 2) d.push_back((points[nn[1]] - points[i]).norm());
  }
  if (d.empty()) return std::nullopt;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

}  // namespace rangefit
