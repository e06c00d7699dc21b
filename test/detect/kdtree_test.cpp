#include "detect/common/kdtree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace rangefit {
namespace kdtree_test {

std::vector<Eigen::Vector3d> RandomPoints(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  std::vector<Eigen::Vector3d> pts(n);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  return pts;
}

TEST(KdTree, EmptyCloudFindsNothing) {
  std::vector<Eigen::Vector3d> none;
  KdTree tree(none);
  std::vector<std::uint32_t> out{7};
  tree.radius_search(Eigen::Vector3d::Zero(), 5.0, out);
  EXPECT_TRUE(out.empty());
  tree.knn_search(Eigen::Vector3d::Zero(), 3, out);
  EXPECT_TRUE(out.empty());
}

TEST(KdTree, RadiusSearchMatchesBruteForce) {
  const auto pts = RandomPoints(2000, 1);
  KdTree tree(pts);
  const Eigen::Vector3d q(1.0, -2.0, 0.5);
  std::vector<std::uint32_t> found;
  tree.radius_search(q, 3.0, found);
  std::vector<std::uint32_t> expected;
  for (std::uint32_t i = 0; i < pts.size(); ++i)
    if ((pts[i] - q).norm() <= 3.0) expected.push_back(i);
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, expected);
  EXPECT_FALSE(expected.empty());
}

TEST(KdTree, KnnReturnsNearestFirst) {
  const auto pts = RandomPoints(500, 2);
  KdTree tree(pts);
  const Eigen::Vector3d q(0.0, 0.0, 0.0);
  std::vector<std::uint32_t> found;
  tree.knn_search(q, 5, found);
  ASSERT_EQ(found.size(), 5u);
  std::vector<std::uint32_t> order(pts.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](auto a, auto b) { return (pts[a] - q).norm() < (pts[b] - q).norm(); });
  for (int i = 0; i < 5; ++i) EXPECT_EQ(found[i], order[i]);
}

}  // namespace kdtree_test
}  // namespace rangefit
