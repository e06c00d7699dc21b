// Concentric walls (thesis fig. 4.33, where the thesis's method fails): a thick-walled pipe's
// inner and outer cylinder told apart without a view direction, by their distance from the CAD
// axis and the CAD radii alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "detect/bore/bore_detector.hpp"
#include "test/detect/bore_test_cases.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit {
namespace bore_pipe_test {

using test::axis_deg;

sim::SyntheticBoreScan pipe_scan(std::uint64_t seed) {
  sim::SyntheticBoreOptions o;
  o.radius = 6.0;
  o.outer_radius = 8.0;
  o.depth = 14.0;
  o.extent = 10.5;
  o.spacing = 0.2;
  o.march_step = 0.05;
  o.seed = seed;
  o.T_world_part = test::random_pose(seed + 1);
  return sim::make_synthetic_bore(o);
}

BorePrior pipe_prior(const sim::SyntheticBoreTruth& t, std::uint64_t seed) {
  BorePrior p = test::perturbed_prior(t, seed);
  p.radius = 6.0;
  p.outer_radius = 8.0;
  return p;
}

TEST(BorePipe, InnerAndOuterWallBothWithoutAViewDirection) {
  for (const std::uint64_t seed : {3u, 4u}) {
    const auto scan = pipe_scan(seed);
    BoreOptions o;  // no view direction, no sensor position
    o.walls = BoreWalls::kBoth;
    const BoreResult r = detect_bore(scan.cloud, pipe_prior(scan.truth, seed), o);
    ASSERT_TRUE(r.found) << to_string(r.reason) << " plane " << r.counts.plane << " wall "
                         << r.counts.wall;
    ASSERT_TRUE(r.outer.has_value());
    ASSERT_TRUE(r.outer->found) << to_string(r.outer->reason) << " wall " << r.outer->wall;
    std::printf(
        "seed %d inner: r %+.4f entrance %.4f axis %.4f | outer: r %+.4f entrance %.4f "
        "axis %.4f (walls %zu / %zu)\n",
        static_cast<int>(seed), r.radius - 6.0, (r.entrance - scan.truth.entrance).norm(),
        axis_deg(r.axis, scan.truth.axis), r.outer->radius - 8.0,
        (r.outer->entrance - scan.truth.entrance).norm(), axis_deg(r.outer->axis, scan.truth.axis),
        r.counts.wall, r.outer->wall);
    EXPECT_NEAR(r.radius, 6.0, 0.05);
    EXPECT_NEAR(r.outer->radius, 8.0, 0.05);
    EXPECT_LT((r.entrance - scan.truth.entrance).norm(), 0.05);
    EXPECT_LT((r.outer->entrance - scan.truth.entrance).norm(), 0.05);
    EXPECT_LT(axis_deg(r.axis, scan.truth.axis), 0.2);
    EXPECT_LT(axis_deg(r.outer->axis, scan.truth.axis), 0.2);
  }
}

TEST(BorePipe, OuterWallAloneAndInnerAloneFindTheirOwnRadius) {
  const auto scan = pipe_scan(5);
  BoreOptions o;
  o.walls = BoreWalls::kOuter;
  const BoreResult outer = detect_bore(scan.cloud, pipe_prior(scan.truth, 5), o);
  ASSERT_TRUE(outer.found) << to_string(outer.reason);
  EXPECT_FALSE(outer.outer.has_value());
  EXPECT_NEAR(outer.radius, 8.0, 0.05);
  o.walls = BoreWalls::kInner;
  const BoreResult inner = detect_bore(scan.cloud, pipe_prior(scan.truth, 5), o);
  ASSERT_TRUE(inner.found) << to_string(inner.reason) << " plane " << inner.counts.plane << " wall "
                           << inner.counts.wall << " roi " << inner.counts.roi;
  EXPECT_NEAR(inner.radius, 6.0, 0.05);
}

TEST(BorePipe, BothWallsNeedAnOuterRadius) {
  const auto scan = pipe_scan(6);
  BorePrior p = pipe_prior(scan.truth, 6);
  p.outer_radius = 0.0;
  BoreOptions o;
  o.walls = BoreWalls::kBoth;
  EXPECT_EQ(detect_bore(scan.cloud, p, o).reason, BoreReason::kBadPrior);
}

}  // namespace bore_pipe_test
}  // namespace rangefit
