#include "calib/stripe_calibration.hpp"

#include <gtest/gtest.h>

#include "calib_fixtures.hpp"

namespace rangefit::test {
namespace stripe_calibration_test {

class StripeCalibrationSeeds : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(StripeCalibrationSeeds, RecoversAPerturbedCellFromOneSweep) {
  const hal::StripeCellGeometry nominal;
  const hal::StripeCellGeometry truth = perturbed_cell(nominal, GetParam());
  const auto r = calibrate(stripe_cube_sweep(truth, {}, 2.0), nominal);
  ASSERT_TRUE(r.ok) << r.reason;
  const double dp = (r.geometry.ranger_position_cell_mm - truth.ranger_position_cell_mm).norm();
  const double da =
      angle_between(r.geometry.T_cell_ranger().linear(), truth.T_cell_ranger().linear());
  const double dd =
      std::acos(std::min(1.0, r.geometry.axis_direction_cell.dot(truth.axis_direction_cell)));
  EXPECT_LT(dp, 0.05);
  EXPECT_LT(da, 0.01 * kDeg);
  EXPECT_LT(dd, 0.01 * kDeg);
  EXPECT_LT(r.rms_mm, 0.01);
  // The start was far off; the linear rounds alone already land on the corners.
  EXPECT_GT((nominal.ranger_position_cell_mm - truth.ranger_position_cell_mm).norm(), 1.0);
  ASSERT_EQ(r.rounds.size(), 3u);
  EXPECT_LT(r.rounds.back().corner_rms_mm, 0.05);
  for (const std::size_t n : r.rounds.back().plane_points) EXPECT_GT(n, 200u);
}

// Seeds drawn for the test, and one whose start is off by the full 10 mm / 3 deg in every field.
INSTANTIATE_TEST_SUITE_P(Perturbed, StripeCalibrationSeeds, ::testing::Values(1u, 2u, 3u));

TEST(StripeCalibration, RecoversACellOffByTheFullRangeInEveryField) {
  const hal::StripeCellGeometry nominal;
  hal::StripeCellGeometry truth = nominal;
  truth.ranger_position_cell_mm += Eigen::Vector3d(10.0, -10.0, 10.0);
  truth.ranger_rpy_cell_rad += Eigen::Vector3d(3.0, -3.0, 3.0) * kDeg;
  truth.axis_direction_cell =
      (Eigen::AngleAxisd(3.0 * kDeg, Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(-3.0 * kDeg, Eigen::Vector3d::UnitZ()) * nominal.axis_direction_cell);
  const auto r = calibrate(stripe_cube_sweep(truth, {}, 2.0), nominal);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_LT((r.geometry.ranger_position_cell_mm - truth.ranger_position_cell_mm).norm(), 0.05);
  EXPECT_LT(angle_between(r.geometry.T_cell_ranger().linear(), truth.T_cell_ranger().linear()),
            0.01 * kDeg);
}

TEST(StripeCalibration, ReportsACovarianceThatMatchesTheNoise) {
  const hal::StripeCellGeometry nominal;
  const hal::StripeCellGeometry truth = perturbed_cell(nominal, 7);
  NormalisedErrors e;
  for (const std::uint64_t seed : {11u, 12u, 13u}) {
    const auto r =
        calibrate(stripe_cube_sweep(truth, {.sigma_mm = 0.06, .seed = seed}, 2.0), nominal);
    ASSERT_TRUE(r.ok) << r.reason;
    e.add(r, truth);
  }
  // A factor of 1.5 in sigma is 2.25 in the mean squared normalised error.
  EXPECT_GT(e.mean(), 1.0 / 2.25);
  EXPECT_LT(e.mean(), 2.25);
}

TEST(StripeCalibration, EmptySweepIsAClearError) {
  const auto r = calibrate(Sweep{}, hal::StripeCellGeometry{});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("too few points"), std::string::npos);
}

TEST(StripeCalibration, SweepThatMissesTheCubeNamesTheMissingPlane) {
  const hal::StripeCellGeometry nominal;
  Sweep s = stripe_cube_sweep(nominal, {}, 4.0);
  // Only the first quarter of the sweep: the laser never reaches most of the cube.
  s.axis.resize(s.axis.size() / 4);
  s.profiles.resize(s.axis.size());
  const auto r = calibrate(s, nominal);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.reason.empty());
}

}  // namespace stripe_calibration_test
}  // namespace rangefit::test
