// Elliptic bores (BorePrior::radius2, major_axis): 10 x 9 mm (axis ratio 0.9) at the CSS's
// density, on every tuning seed (test/detect/bore_test_cases.hpp; the held-out seeds are
// reported by bore_benchmark).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "detect/bore_detector.hpp"
#include "test/detect/bore_test_cases.hpp"

namespace rangefit {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

double axis_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.dot(b)))) * kRadToDeg;
}

TEST(BoreEllipse, RadiiMajorAxisEntranceAndAxisOnEveryTuningSeed) {
  for (std::uint64_t seed = 1; seed <= test::kShapeTuningSeeds; ++seed) {
    const test::ShapeRun run = test::detect_shape(test::ShapeKind::kEllipse, seed);
    const sim::SyntheticBoreTruth& t = run.scan.truth;
    const BoreResult& r = run.result;
    ASSERT_TRUE(r.found) << "seed " << seed << ": " << to_string(r.reason);
    ASSERT_TRUE(r.shape.has_value());
    ASSERT_FALSE(r.shape->cone);
    const double entrance_err = (r.entrance - t.entrance).norm();
    const double axis_err = axis_deg(r.axis, t.axis);
    const double major_err = axis_deg(r.shape->major_axis, t.major_axis);
    std::printf(
        "ellipse seed %d: radius %+.4f (sigma %.4f) radius2 %+.4f (sigma %.4f) mm, major axis "
        "%.3f deg, entrance %.4f mm, axis %.4f deg, %zu points, rms %.3f, rsf seed %d, %.1f ms\n",
        static_cast<int>(seed), r.radius - t.radius, r.shape->sigma_radius,
        r.shape->radius2 - t.radius2, r.shape->sigma_radius2, major_err, entrance_err, axis_err,
        r.counts.refine_inliers, r.shape->rms, r.shape->seeded_by_rsf ? 1 : 0, r.time_ms.total);
    EXPECT_NEAR(r.radius, t.radius, 0.02) << "seed " << seed;
    EXPECT_NEAR(r.shape->radius2, t.radius2, 0.02) << "seed " << seed;
    EXPECT_LT(major_err, 2.0) << "seed " << seed;
    EXPECT_LT(entrance_err, 0.1) << "seed " << seed;
    EXPECT_LT(axis_err, 0.2) << "seed " << seed;
  }
}

TEST(BoreEllipse, EmptyCloudIsAnEmptyRegion) {
  const auto scan =
      sim::make_synthetic_bore(test::shape_scan_options(test::ShapeKind::kEllipse, 1));
  const BoreResult r = detect_bore(PointCloud{}, test::shape_prior(scan.truth, 1));
  EXPECT_EQ(r.reason, BoreReason::kEmptyRoi);
}

TEST(BoreEllipse, MajorAxisAlongTheBoreAxisIsABadModel) {
  const auto scan =
      sim::make_synthetic_bore(test::shape_scan_options(test::ShapeKind::kEllipse, 1));
  BorePrior p = test::shape_prior(scan.truth, 1);
  p.major_axis = p.axis;
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadShape);
  p.major_axis = Eigen::Vector3d::Zero();
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadShape);
}

}  // namespace
}  // namespace rangefit
