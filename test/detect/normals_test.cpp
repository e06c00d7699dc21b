#include "detect/common/normals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "detect/common/normals_grid.hpp"
#include "test/support/ordered_draws.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit {
namespace normals_test {

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
  for (const int method : {0, 1, 2}) {
    const bool organised = method == 1;
    const PointCloud c = plate(organised);
    const KdTree tree(c.points);
    NormalOptions o;
    o.view_dir = -Eigen::Vector3d::UnitZ();
    const auto idx = all(c);
    const NormalEstimate e = method == 1   ? estimate_normals_organised(c, idx, o)
                             : method == 2 ? estimate_normals_binned(c.points, idx, o)
                                           : estimate_normals(c.points, tree, idx, o);
    ASSERT_EQ(e.normals.size(), c.size());
    std::size_t centre_kept = 0, corner_kept = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const bool corner = std::abs(c.points[i].x()) > 4.5 && std::abs(c.points[i].y()) > 4.5;
      if (e.normals[i].isZero()) continue;
      EXPECT_NEAR(e.normals[i].z(), -1.0, 1e-9) << "method " << method;
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

TEST(Normals, BinnedGridOfNoPointsGivesNoNormals) {
  const std::vector<Eigen::Vector3d> none;
  const std::vector<std::uint32_t> one{0};
  EXPECT_TRUE(estimate_normals_binned(none, {}, {}).normals.empty());
  // An out-of-range query index gets no normal instead of a crash.
  EXPECT_EQ(estimate_normals_binned(none, one, {}).kept, 0u);
}

// The binned grid must find the k-d tree's neighbourhoods: same kept set, same normals, on a
// noisy bore scan with outliers and ghosts (the detector's real input).
TEST(Normals, BinnedNormalsMatchTheKdTreeOnANoisyBoreScan) {
  sim::SyntheticBoreOptions so;
  so.seed = 5;
  so.slant_deg = 30.0;
  const sim::SyntheticBoreScan scan = sim::make_synthetic_bore(so);
  const auto& pts = scan.cloud.points;
  const KdTree tree(pts);
  NormalOptions o;
  o.view_dir = scan.truth.view_dir;
  const auto idx = all(scan.cloud);
  const NormalEstimate a = estimate_normals(pts, tree, idx, o);
  const NormalEstimate b = estimate_normals_binned(pts, idx, o);
  ASSERT_EQ(b.normals.size(), a.normals.size());
  ASSERT_GT(a.kept, pts.size() / 2);
  std::size_t differ = 0, off = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < idx.size(); ++i) {
    if (a.normals[i].isZero() != b.normals[i].isZero()) {
      ++differ;  // only a centroid offset within float rounding of 0.1 R may flip
    } else if (!a.normals[i].isZero()) {
      const double d = (a.normals[i] - b.normals[i]).norm();
      worst = std::max(worst, d);
      if (d > 1e-4) ++off;
    }
  }
  EXPECT_LE(differ, a.kept / 1000 + 1);
  // The scan's lattice puts many neighbours at |x - p| = R to within float rounding: one may be
  // in one set and not the other, which moves a normal by ~1e-4 at most on a full patch.
  EXPECT_LE(off, a.kept / 100) << "normals must agree to within float rounding";
  EXPECT_LT(worst, 0.05);
}

TEST(Normals, BinnedBallCountsExactlyThePointsWithinTheRadius) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<Eigen::Vector3d> pts;
  const Eigen::Vector3d squash(1.0, 1.0, 0.3);
  for (int i = 0; i < 3000; ++i) pts.push_back(squash.asDiagonal() * test::draw3(u, rng));
  const NeighbourGrid grid(pts, Eigen::Vector3d(0.2, -0.1, 1.0), 0.4);
  for (int q = 0; q < 50; ++q) {
    const Eigen::Vector3d p = squash.asDiagonal() * test::draw3(u, rng);
    double n = 0.0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& x : pts) {
      if ((x - p).squaredNorm() <= 1.5 * 1.5) {
        n += 1.0;
        sum += x - p;
      }
    }
    const pca::Moments m = grid.ball(p, 1.5);
    EXPECT_EQ(m.count, n);
    EXPECT_LT((m.sum - sum).norm(), 1e-4);
  }
  EXPECT_EQ(grid.ball(Eigen::Vector3d::Constant(NAN), 1.5).count, 0.0);
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

}  // namespace normals_test
}  // namespace rangefit
