// The final least-squares refinement on every region point near the RSF cylinder (the default)
// against the refinement on the Gaussian-image wall points only (session 1), over all synthetic
// cases: the median errors must not get worse, and no case may leave the thesis's tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "detect/bore/bore_detector.hpp"
#include "test/detect/bore_test_cases.hpp"

namespace rangefit {
namespace bore_refine_test {

struct Medians {
  double entrance_mm = 0, axis_deg = 0, radius_mm = 0;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

Medians run_all(bool all_region_points) {
  std::vector<double> entrance, axis, radius;
  for (const auto& c : test::bore_cases()) {
    const auto scan = sim::make_synthetic_bore(c.scan);
    BoreOptions opt;
    opt.view_dir = scan.truth.view_dir;
    opt.refine_all_region_points = all_region_points;
    const BoreResult r =
        detect_bore(scan.cloud, test::perturbed_prior(scan.truth, c.scan.seed), opt);
    EXPECT_TRUE(r.found) << c.name << ": " << to_string(r.reason);
    if (all_region_points) {
      EXPECT_TRUE(r.refined) << c.name;
    }
    if (!r.found) continue;
    entrance.push_back((r.entrance - scan.truth.entrance).norm());
    axis.push_back(std::acos(std::clamp(r.axis.dot(scan.truth.axis), -1.0, 1.0)) * 180.0 /
                   std::numbers::pi);
    radius.push_back(std::abs(r.radius - scan.truth.radius));
    EXPECT_LT(entrance.back(), 0.3) << c.name;
    EXPECT_LT(axis.back(), 0.5) << c.name;
    EXPECT_LT(radius.back(), 0.3) << c.name;
  }
  return {median(entrance), median(axis), median(radius)};
}

TEST(BoreRefine, EveryRegionPointNearTheWallIsAtLeastAsAccurateAsWallPointsAlone) {
  const Medians wall_only = run_all(false);
  const Medians region = run_all(true);
  std::printf("median over the cases  entrance / axis / |radius|\n");
  std::printf("  wall points only     %.4f mm / %.4f deg / %.4f mm\n", wall_only.entrance_mm,
              wall_only.axis_deg, wall_only.radius_mm);
  std::printf("  all region points    %.4f mm / %.4f deg / %.4f mm\n", region.entrance_mm,
              region.axis_deg, region.radius_mm);
  EXPECT_LE(region.entrance_mm, wall_only.entrance_mm);
  EXPECT_LE(region.axis_deg, wall_only.axis_deg);
  EXPECT_LE(region.radius_mm, wall_only.radius_mm);
}

TEST(BoreRefine, RefinementUsesMorePointsThanTheSegmentedWall) {
  const auto cases = test::bore_cases();
  const auto scan = sim::make_synthetic_bore(cases.front().scan);
  BoreOptions opt;
  opt.view_dir = scan.truth.view_dir;
  const BoreResult r =
      detect_bore(scan.cloud, test::perturbed_prior(scan.truth, cases.front().scan.seed), opt);
  ASSERT_TRUE(r.found);
  // The Gaussian image keeps the wall points whose whole R-neighbourhood is cylindrical; the
  // band adds those near the rim, the bottom and the normal-less ones in between.
  EXPECT_GT(r.counts.refine_inliers, r.counts.wall * 3 / 2);
}

}  // namespace bore_refine_test
}  // namespace rangefit
