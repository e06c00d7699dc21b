#include "detect/normals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

namespace rangefit {
namespace {

// A flat 10 x 10 mm grid at z = 0 with 0.2 mm spacing, optionally organised.
PointCloud plate(bool organised) {
  PointCloud c;
  const int n = 51;
  if (organised) {
    c.grid.rows = c.grid.cols = n;
    c.grid.index.resize(static_cast<std::size_t>(n) * n);
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (organised) c.grid.index[static_cast<std::size_t>(i) * n + j] = i * n + j;
      c.points.emplace_back(0.2 * i - 5.0, 0.2 * j - 5.0, 0.0);
    }
  }
  return c;
}

std::vector<std::uint32_t> all(const PointCloud& c) {
  std::vector<std::uint32_t> idx(c.size());
  std::iota(idx.begin(), idx.end(), 0u);
  return idx;
}

TEST(Normals, EmptyQueriesGiveNoNormals) {
  const PointCloud c = plate(false);
  const KdTree tree(c.points);
  EXPECT_TRUE(estimate_normals(c.points, tree, {}, {}).normals.empty());
  EXPECT_EQ(estimate_normals_organised(c, {}, {}).kept, 0u);
}

TEST(Normals, PlateNormalsPointTowardTheViewAndBoundaryPatchesAreRejected) {
  for (const bool organised : {false, true}) {
    const PointCloud c = plate(organised);
    const KdTree tree(c.points);
    NormalOptions o;
    o.view_dir = -Eigen::Vector3d::UnitZ();
    const auto idx = all(c);
    const NormalEstimate e = organised ? estimate_normals_organised(c, idx, o)
                                       : estimate_normals(c.points, tree, idx, o);
    ASSERT_EQ(e.normals.size(), c.size());
    std::size_t centre_kept = 0, corner_kept = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const bool corner = std::abs(c.points[i].x()) > 4.5 && std::abs(c.points[i].y()) > 4.5;
      if (e.normals[i].isZero()) continue;
      EXPECT_NEAR(e.normals[i].z(), -1.0, 1e-9) << "organised " << organised;
      if (corner) ++corner_kept;
      if (c.points[i].head<2>().norm() < 2.0) ++centre_kept;
    }
    EXPECT_EQ(corner_kept, 0u) << "eq. 4.4 must reject the off-centre corner patches";
    EXPECT_GT(centre_kept, 300u);
  }
}

TEST(Normals, SensorPositionOrientsEachNormal) {
  const PointCloud c = plate(false);
  const KdTree tree(c.points);
  NormalOptions o;
  o.sensor_position = Eigen::Vector3d(0, 0, 100);
  const std::vector<std::uint32_t> centre{1300};
  EXPECT_NEAR(estimate_normals(c.points, tree, centre, o).normals[0].z(), 1.0, 1e-9);
}

TEST(Normals, SubsamplingKeepsTheRequestedShareEvenly) {
  std::vector<std::uint32_t> idx(1000);
  std::iota(idx.begin(), idx.end(), 0u);
  const auto kept = subsample_evenly(idx, 0.2);
  EXPECT_EQ(kept.size(), 200u);
  EXPECT_EQ(kept[1] - kept[0], 5u);
  EXPECT_TRUE(subsample_evenly(idx, 0.0).empty());
  EXPECT_EQ(subsample_evenly(idx, 1.0).size(), 1000u);
}

}  // namespace
}  // namespace rangefit
