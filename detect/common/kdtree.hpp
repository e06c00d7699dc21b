#pragma once
// Radius and k-nearest neighbour search over an unorganised cloud (nanoflann k-d tree, kept out
// of this header). The tree references the points it was built from: they must outlive it.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace rangefit {

class KdTree {
 public:
  explicit KdTree(std::span<const Eigen::Vector3d> points);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;
  KdTree(const KdTree&) = delete;
  KdTree& operator=(const KdTree&) = delete;

  // Replaces `out` with the indices of all points within `radius` (mm) of `query`, unordered.
  void radius_search(const Eigen::Vector3d& query, double radius,
                     std::vector<std::uint32_t>& out) const;

  // Replaces `out` with the indices of the k nearest points, nearest first (fewer if the cloud
  // has fewer than k points).
  void knn_search(const Eigen::Vector3d& query, std::size_t k,
                  std::vector<std::uint32_t>& out) const;

  std::size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The scan's point spacing about the points `which` (indices into the tree's points): the median
// distance from each to its nearest other point. nullopt when none of them has a neighbour.
std::optional<double> median_neighbour_distance(std::span<const Eigen::Vector3d> points,
                                                const KdTree& tree,
                                                std::span<const std::uint32_t> which);

}  // namespace rangefit
