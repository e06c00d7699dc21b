#include <gtest/gtest.h>

#include <limits>

#include "detect/bore/bore_detector.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit {
namespace bore_reasons_test {

sim::SyntheticBoreScan plate_scan() {
  sim::SyntheticBoreOptions o;
  o.seed = 11;
  return sim::make_synthetic_bore(o);
}

BorePrior truth_prior(const sim::SyntheticBoreTruth& t) {
  BorePrior p;
  p.entrance = t.entrance;
  p.axis = t.axis;
  p.radius = t.radius;
  p.plane_normal = t.plane_normal;
  return p;
}

TEST(BoreReasons, EmptyCloudIsAnEmptyRegion) {
  const BoreResult r = detect_bore(PointCloud{}, truth_prior(plate_scan().truth));
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.reason, BoreReason::kEmptyRoi);
}

TEST(BoreReasons, NanPriorIsBadInput) {
  const auto scan = plate_scan();
  BorePrior p = truth_prior(scan.truth);
  p.entrance.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadPrior);
  p = truth_prior(scan.truth);
  p.radius = 0.0;
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kBadPrior);
}

TEST(BoreReasons, NanPointsAreSkippedAndCounted) {
  auto scan = plate_scan();
  for (std::size_t i = 0; i < scan.cloud.size(); i += 50) {
    scan.cloud.points[i] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  BoreOptions o;
  o.view_dir = scan.truth.view_dir;
  const BoreResult r = detect_bore(scan.cloud, truth_prior(scan.truth), o);
  EXPECT_TRUE(r.found) << to_string(r.reason);
  EXPECT_EQ(r.counts.non_finite, (scan.cloud.size() + 49) / 50);
}

TEST(BoreReasons, PriorFarFromTheScanIsAnEmptyRegion) {
  const auto scan = plate_scan();
  BorePrior p = truth_prior(scan.truth);
  p.entrance += Eigen::Vector3d(500, 0, 0);
  EXPECT_EQ(detect_bore(scan.cloud, p).reason, BoreReason::kEmptyRoi);
}

TEST(BoreReasons, CollinearPointsHaveDegenerateNormals) {
  PointCloud line;
  for (int i = 0; i < 200; ++i) line.points.emplace_back(0.05 * i - 5.0, 0.0, 0.0);
  BorePrior p;
  p.radius = 5.0;
  EXPECT_EQ(detect_bore(line, p).reason, BoreReason::kDegenerateNormals);
}

TEST(BoreReasons, PlateWithoutBoreHasTooFewWallPoints) {
  PointCloud plate;
  for (int i = -50; i <= 50; ++i) {
    for (int j = -50; j <= 50; ++j) plate.points.emplace_back(0.2 * i, 0.2 * j, 0.0);
  }
  BorePrior p;
  p.radius = 5.0;
  EXPECT_EQ(detect_bore(plate, p).reason, BoreReason::kTooFewWallPoints);
}

TEST(BoreReasons, WallWithoutPlateHasNoPlane) {
  auto scan = plate_scan();
  BorePrior p = truth_prior(scan.truth);
  p.plane_normal = scan.truth.plane_normal.unitOrthogonal();  // no surface faces this way
  BoreOptions o;
  o.view_dir = scan.truth.view_dir;
  EXPECT_EQ(detect_bore(scan.cloud, p, o).reason, BoreReason::kNoPlane);
}

TEST(BoreReasons, SameSeedGivesTheSameResult) {
  const auto scan = plate_scan();
  BoreOptions o;
  o.view_dir = scan.truth.view_dir;
  const BoreResult a = detect_bore(scan.cloud, truth_prior(scan.truth), o);
  const BoreResult b = detect_bore(scan.cloud, truth_prior(scan.truth), o);
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.entrance, b.entrance);
  EXPECT_EQ(a.radius, b.radius);
}

}  // namespace bore_reasons_test
}  // namespace rangefit
