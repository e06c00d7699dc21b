#include "fusion/css_assembler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <functional>

#include "test/fusion/css_truth.hpp"

namespace rangefit::fusion {
namespace css_assembler_test {

using std::chrono::milliseconds;
using testing::CssTruthOptions;
using testing::make_css_truth;

constexpr int kCols = hal::CssRevolution::kSamples;

// Largest distance between a fused point and its true hit, over every valid cell; also checks
// that fused and true cells agree on which ones are valid.
// With a bound, the error of each point is divided by bound(true hit).
double max_error(const FusedScan& scan, const testing::CssTruthScan& truth,
                 const std::function<double(const Eigen::Vector3d&)>& bound = {}) {
  double worst = 0.0;
  for (int r = 0; r < scan.cloud.grid.rows; ++r) {
    for (int c = 0; c < kCols; ++c) {
      const Eigen::Vector3d& hit =
          truth.hits[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
      const std::int32_t k = scan.cloud.grid.at(r, c);
      EXPECT_EQ(k >= 0, !std::isnan(hit.x())) << "row " << r << " col " << c;
      if (k < 0 || std::isnan(hit.x())) continue;
      double e = (scan.cloud.points[static_cast<std::size_t>(k)] - hit).norm();
      if (bound) e /= bound(hit);
      worst = std::max(worst, e);
    }
  }
  return worst;
}

TEST(CssAssembler, EveryFusedPointIsWithinAMicrometreOfTheTrueHit) {
  const CssFusionConfig config;
  const auto truth = make_css_truth(config, CssTruthOptions{});
  const FusedScan scan = fuse_css_scan(config, truth.revolutions, truth.joints);
  ASSERT_EQ(scan.cloud.grid.rows, 20);
  EXPECT_GT(scan.cloud.size(), 20u * 400u);
  EXPECT_LT(max_error(scan, truth), 0.001);
  EXPECT_EQ(scan.faults.total(), 0u);
  EXPECT_FALSE(scan.bad);
}

TEST(CssAssembler, JointStampJitterOfOneMillisecondStaysWithinTheErrorItImplies) {
  const CssFusionConfig config;
  CssTruthOptions o;
  o.joint_jitter = milliseconds(1);
  const auto truth = make_css_truth(config, o);
  const FusedScan scan = fuse_css_scan(config, truth.revolutions, truth.joints);
  // omega is interpolated between samples whose stamps are off by at most 1 ms, so it is off by
  // at most omega_dot * 1 ms; a point at distance rho from the joint axis (world y) moves by at
  // most rho times that. 1e-5 mm covers the float ranges.
  const double omega_error = truth.omega_rate_rad_s * 1e-3;
  const auto bound = [omega_error](const Eigen::Vector3d& p) {
    return omega_error * std::hypot(p.x(), p.z()) + 1e-5;
  };
  EXPECT_LE(max_error(scan, truth, bound), 1.0);
  // The jitter does matter: the error exceeds what exact stamps give (< 0.001 mm).
  EXPECT_GT(max_error(scan, truth), 0.001);
}

TEST(CssAssembler, StartEndStampFallbackMatchesTheTruthWithoutAJointStream) {
  CssFusionConfig config;
  config.omega_source = OmegaSource::kStartEndStamps;
  const auto truth = make_css_truth(config, CssTruthOptions{});
  const FusedScan scan = fuse_css_scan(config, truth.revolutions, {}, truth.t_start, truth.t_end);
  ASSERT_EQ(scan.cloud.grid.rows, 20);
  EXPECT_LT(max_error(scan, truth), 0.001);
  EXPECT_EQ(scan.faults.total(), 0u);
}

TEST(CssAssembler, FallbackWithoutEndStampUsesTheConfiguredScanSpeed) {
  CssFusionConfig config;
  config.omega_source = OmegaSource::kStartEndStamps;
  const auto truth = make_css_truth(config, CssTruthOptions{});
  // t_start = 0: the first revolution's stamp, which is the truth's t_start.
  const FusedScan scan = fuse_css_scan(config, truth.revolutions, {});
  EXPECT_LT(max_error(scan, truth), 0.001);
}

TEST(CssAssembler, CloudIsOrganisedRevolutionBySampleWithPerSampleStamps) {
  const CssFusionConfig config;
  CssTruthOptions o;
  o.revolutions = 3;
  auto truth = make_css_truth(config, o);
  truth.revolutions[1].range_mm[17] = hal::kNoReturn;
  truth.hits[1][17] = Eigen::Vector3d::Constant(std::nan(""));
  const FusedScan scan = fuse_css_scan(config, truth.revolutions, truth.joints);
  ASSERT_EQ(scan.cloud.grid.rows, 3);
  ASSERT_EQ(scan.cloud.grid.cols, kCols);
  EXPECT_EQ(scan.cloud.grid.at(1, 17), -1);
  ASSERT_TRUE(scan.cloud.has_stamps());
  const std::int32_t k = scan.cloud.grid.at(2, 256);
  ASSERT_GE(k, 0);
  EXPECT_EQ(scan.cloud.stamps[static_cast<std::size_t>(k)],
            truth.revolutions[2].stamp + o.period / 2);
  ASSERT_EQ(scan.frames.size(), 3u);
  EXPECT_EQ(scan.frames[2].sequence, truth.revolutions[2].sequence);
  EXPECT_EQ(scan.cloud.frame_id, "world");
}

TEST(CssAssembler, EmptyScanGivesAnEmptyCloudWithoutFaults) {
  CssAssembler assembler{CssFusionConfig{}};
  const FusedScan scan = assembler.finish();
  EXPECT_TRUE(scan.cloud.empty());
  EXPECT_EQ(scan.cloud.grid.rows, 0);
  EXPECT_EQ(scan.faults.total(), 0u);
  EXPECT_FALSE(scan.bad);
}

TEST(CssAssembler, RevolutionIsFusedTheMomentTheJointStreamCoversIt) {
  const CssFusionConfig config;
  CssTruthOptions o;
  o.revolutions = 2;
  const auto truth = make_css_truth(config, o);
  CssAssembler assembler(config);
  const hal::Timestamp first_end = truth.revolutions[0].stamp + o.period;
  std::size_t j = 0;
  for (; truth.joints[j].stamp < first_end - milliseconds(20); ++j)
    assembler.add_joint(truth.joints[j]);
  EXPECT_EQ(assembler.add_revolution(truth.revolutions[0]), 0u);  // waits for the joint stream
  EXPECT_EQ(assembler.pending(), 1u);
  std::size_t fused = 0;
  for (; j < truth.joints.size() && fused == 0; ++j) fused = assembler.add_joint(truth.joints[j]);
  EXPECT_EQ(fused, 1u);
  EXPECT_EQ(assembler.scan().cloud.grid.rows, 1);
  for (; j < truth.joints.size(); ++j) assembler.add_joint(truth.joints[j]);
  EXPECT_EQ(assembler.add_revolution(truth.revolutions[1]), 1u);  // covered: fused at once
  const FusedScan scan = assembler.finish();
  EXPECT_EQ(scan.cloud.grid.rows, 2);
  EXPECT_LT(max_error(scan, truth), 0.001);
}

TEST(CssAssembler, AssemblerIsReusableForTheNextScan) {
  const CssFusionConfig config;
  const auto truth = make_css_truth(config, CssTruthOptions{});
  CssAssembler assembler(config);
  for (int pass = 0; pass < 2; ++pass) {
    assembler.begin_scan();
    for (const auto& s : truth.joints) assembler.add_joint(s);
    for (const auto& r : truth.revolutions) assembler.add_revolution(r);
    const FusedScan scan = assembler.finish();
    EXPECT_EQ(scan.cloud.grid.rows, 20);
    EXPECT_EQ(scan.faults.total(), 0u);
  }
}

}  // namespace css_assembler_test
}  // namespace rangefit::fusion
