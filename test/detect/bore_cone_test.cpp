// Conical bores (BorePrior::half_angle): a 90 deg countersink into a cylindrical bore, a pure
// 90 deg cone and a 3 deg taper at the CSS's density, on every tuning seed
// (test/detect/bore_test_cases.hpp; the held-out seeds are reported by bore_benchmark).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "detect/bore/bore_detector.hpp"
#include "test/detect/bore_test_cases.hpp"

namespace rangefit {
namespace bore_cone_test {

using test::axis_deg;
using test::kRadToDeg;

class BoreCone : public ::testing::TestWithParam<test::ShapeKind> {};

TEST_P(BoreCone, AngleEntranceAndAxisOnEveryTuningSeed) {
  for (std::uint64_t seed = 1; seed <= test::kShapeTuningSeeds; ++seed) {
    const test::ShapeRun run = test::detect_shape(GetParam(), seed);
    const sim::SyntheticBoreTruth& t = run.scan.truth;
    const BoreResult& r = run.result;
    ASSERT_TRUE(r.found) << "seed " << seed << ": " << to_string(r.reason);
    ASSERT_TRUE(r.shape.has_value());
    ASSERT_TRUE(r.shape->cone);
    const double angle_err = (r.shape->half_angle - t.half_angle) * kRadToDeg;
    const double entrance_err = (r.entrance - t.entrance).norm();
    const double axis_err = axis_deg(r.axis, t.axis);
    std::printf(
        "%s seed %d: half-angle %+.4f deg (sigma %.4f), entrance %.4f mm, axis %.4f deg, "
        "radius %+.4f mm, cylinder %+.4f mm, %zu points, rms %.3f, rsf seed %d, %.1f ms\n",
        test::shape_name(GetParam()), static_cast<int>(seed), angle_err,
        r.shape->sigma_half_angle * kRadToDeg, entrance_err, axis_err, r.radius - t.cone_radius,
        r.shape->cylinder_radius > 0.0 ? r.shape->cylinder_radius - t.radius : 0.0,
        r.counts.refine_inliers, r.shape->rms, r.shape->seeded_by_rsf ? 1 : 0, r.time_ms.total);
    EXPECT_LT(std::abs(angle_err), 0.2) << "seed " << seed;
    EXPECT_LT(entrance_err, 0.1) << "seed " << seed;
    EXPECT_LT(axis_err, 0.2) << "seed " << seed;
    EXPECT_NEAR(r.radius, t.cone_radius, 0.05) << "seed " << seed;
    EXPECT_GT(r.axis.dot(t.axis), 0.0);  // out of the bore
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, BoreCone,
                         ::testing::Values(test::ShapeKind::kCountersink, test::ShapeKind::kCone,
                                           test::ShapeKind::kTaper),
                         [](const auto& kind) {
                           switch (kind.param) {
                             case test::ShapeKind::kCountersink:
                               return std::string("Countersink90");
                             case test::ShapeKind::kCone:
                               return std::string("Cone90");
                             default:
                               return std::string("Taper3deg");
                           }
                         });

TEST(BoreConeReasons, EmptyCloudIsAnEmptyRegion) {
  const auto scan =
      sim::make_synthetic_bore(test::shape_scan_options(test::ShapeKind::kCountersink, 1));
  const BoreResult r = detect_bore(PointCloud{}, test::shape_prior(scan.truth, 1));
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.reason, BoreReason::kEmptyRoi);
  EXPECT_FALSE(r.shape.has_value());
}

TEST(BoreConeReasons, BadConeModelsAreRefusedWithTheirReason) {
  const auto scan =
      sim::make_synthetic_bore(test::shape_scan_options(test::ShapeKind::kCountersink, 1));
  const BorePrior good = test::shape_prior(scan.truth, 1);
  BorePrior p = good;
  p.half_angle = 1.5;  // beyond 80 deg
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadShape);
  p = good;
  p.radius2 = 5.0;  // a cone and an ellipse at once
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadShape);
  p = good;
  p.cylinder_radius = p.radius + 1.0;  // the cone would widen into its cylinder
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadShape);
  p = good;
  p.half_angle = 0.0;  // a cylinder radius without a cone
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadShape);
  BoreOptions o;
  o.walls = BoreWalls::kBoth;  // pipes are cylinders
  p = good;
  p.outer_radius = 8.0;
  EXPECT_EQ(detect_bore(scan.cloud, p, o).reason, BoreReason::kBadShape);
  EXPECT_NE(to_string(BoreReason::kBadShape).find("cone"), std::string_view::npos);
}

// The wrong model: a 90 deg countersink prior on a plain cylindrical bore finds no cone wall
// near the model (or one that leaves it) and says so instead of reporting a cone.
TEST(BoreConeReasons, CountersinkPriorOnAPlainBoreIsNotFound) {
  sim::SyntheticBoreOptions so = test::shape_scan_options(test::ShapeKind::kCountersink, 2);
  so.cone_radius = 0.0;
  so.radius = 6.0;
  const auto scan = sim::make_synthetic_bore(so);
  BorePrior p = test::perturbed_prior(scan.truth, 2);
  p.radius = 6.0;
  p.half_angle = std::numbers::pi / 4;
  p.cylinder_radius = 3.0;
  BoreOptions o;
  o.view_dir = scan.truth.view_dir;
  const BoreResult r = detect_bore(scan.cloud, p, o);
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.reason, BoreReason::kShapeFitFailed) << to_string(r.reason);
}

}  // namespace bore_cone_test
}  // namespace rangefit
