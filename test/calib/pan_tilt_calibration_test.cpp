#include "calib/pan_tilt_calibration.hpp"

#include <gtest/gtest.h>

#include "pan_tilt_fixtures.hpp"

namespace rangefit::test {
namespace pan_tilt_calibration_test {

void expect_recovered(const calib::PanTiltCalibrationResult& r, const hal::PanTiltGeometry& truth) {
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_LT((r.geometry.t_s_mm - truth.t_s_mm).norm(), 0.05);
  EXPECT_LT((r.geometry.t_w_mm - truth.t_w_mm).norm(), 0.05);
  EXPECT_NEAR(r.geometry.pan_zero_rad, truth.pan_zero_rad, 0.01 * kDeg);
  EXPECT_NEAR(r.geometry.tilt_zero_rad, truth.tilt_zero_rad, 0.01 * kDeg);
  // Where it matters: a ranger point at 750 mm lands where the true head puts it.
  for (const double pan : {-0.15, 0.0, 0.15}) {
    const Eigen::Vector3d q(40.0, 0.0, 750.0);
    EXPECT_LT(
        (r.geometry.T_world_ranger(pan, 0.05) * q - truth.T_world_ranger(pan, 0.05) * q).norm(),
        0.05);
  }
}

class PanTiltCalibrationSeeds : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(PanTiltCalibrationSeeds, RecoversAPerturbedHeadFromSweepsAtThreeTilts) {
  const hal::PanTiltGeometry nominal = configured_head();
  const hal::PanTiltGeometry truth = perturbed_head(nominal, GetParam());
  const auto r = run_pan_tilt(pan_tilt_sweeps(truth, 0.0, 1), nominal);
  expect_recovered(r, truth);
  EXPECT_LT(r.rms_mm, 0.01);
  EXPECT_GT(r.initial_rms_mm, 1.0);  // the start was visibly off
  ASSERT_EQ(r.rounds.size(), 3u);
  EXPECT_GT(r.points, 3000u);
}

INSTANTIATE_TEST_SUITE_P(Perturbed, PanTiltCalibrationSeeds, ::testing::Values(1u, 2u, 3u));

TEST(PanTiltCalibration, RecoversAHeadOffByTheFullRangeInEveryField) {
  const hal::PanTiltGeometry nominal = configured_head();
  hal::PanTiltGeometry truth = nominal;
  truth.t_s_mm += Eigen::Vector3d(10.0, -10.0, 10.0);
  truth.t_w_mm += Eigen::Vector3d(-10.0, 10.0, -10.0);
  truth.pan_zero_rad = 3.0 * kDeg;
  truth.tilt_zero_rad = -3.0 * kDeg;
  expect_recovered(run_pan_tilt(pan_tilt_sweeps(truth, 0.0, 1), nominal), truth);
}

TEST(PanTiltCalibration, ReportsACovarianceThatMatchesTheNoise) {
  const hal::PanTiltGeometry nominal = configured_head();
  const hal::PanTiltGeometry truth = perturbed_head(nominal, 7);
  double z2 = 0.0;
  int count = 0;
  for (const std::uint64_t seed : {11u, 21u, 31u}) {
    const auto r = run_pan_tilt(pan_tilt_sweeps(truth, 0.06, seed), nominal);
    ASSERT_TRUE(r.ok) << r.reason;
    Eigen::Matrix<double, 8, 1> e;
    e << r.geometry.t_s_mm - truth.t_s_mm, r.geometry.t_w_mm - truth.t_w_mm,
        r.geometry.pan_zero_rad - truth.pan_zero_rad,
        r.geometry.tilt_zero_rad - truth.tilt_zero_rad;
    for (int k = 0; k < 8; ++k) {
      z2 += e[k] * e[k] / r.covariance(k, k);
      ++count;
    }
  }
  // Mean squared normalised error: 1 when the covariance is right; a factor of 1.5 in sigma is
  // 2.25 in it.
  const double mean = z2 / count;
  EXPECT_GT(mean, 1.0 / 2.25);
  EXPECT_LT(mean, 2.25);
}

TEST(PanTiltCalibration, OneTiltIsAClearError) {
  const hal::PanTiltGeometry nominal = configured_head();
  const auto r = run_pan_tilt(pan_tilt_sweeps(nominal, 0.0, 1, {0.0}, 0.5), nominal);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("two or more tilt angles"), std::string::npos) << r.reason;
  EXPECT_FALSE(run_pan_tilt(PanTiltSweeps{}, nominal).ok);
  // Two sweeps, both at the same tilt.
  const auto same = run_pan_tilt(pan_tilt_sweeps(nominal, 0.0, 1, {3.0, 3.0}, 0.5), nominal);
  EXPECT_FALSE(same.ok);
  EXPECT_NE(same.reason.find("two or more tilt angles"), std::string::npos) << same.reason;
}

TEST(PanTiltCalibration, SweepsThatMissTheCubeNameTheMissingPlanes) {
  const hal::PanTiltGeometry nominal = configured_head();
  PanTiltSweeps s = pan_tilt_sweeps(nominal, 0.0, 1, {-6.0, 6.0}, 0.5);
  // Only the first sixth of each sweep: the laser never reaches most of the cube.
  for (std::size_t k = 0; k < s.angles.size(); ++k) {
    s.angles[k].resize(s.angles[k].size() / 6);
    s.profiles[k].resize(s.angles[k].size());
  }
  const auto r = run_pan_tilt(s, nominal);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.reason.empty());
}

}  // namespace pan_tilt_calibration_test
}  // namespace rangefit::test
