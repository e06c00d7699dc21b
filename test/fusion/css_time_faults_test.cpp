// One test per time-alignment fault kind of the CSS assembler: each is detected, counted in the
// scan's metadata, and never smoothed over; past the limit the scan is marked bad.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include "fusion/css_assembler.hpp"
#include "test/fusion/css_truth.hpp"

namespace rangefit::fusion {
namespace css_time_faults_test {

using std::chrono::milliseconds;
using testing::CssTruthOptions;
using testing::make_css_truth;

FusedScan fuse(const CssFusionConfig& config, const std::vector<hal::CssRevolution>& revs,
               const std::vector<hal::JointSample>& joints) {
  return fuse_css_scan(config, revs, joints);
}

// Largest distance between corresponding points of two scans of the same cells.
double max_difference(const FusedScan& a, const FusedScan& b) {
  EXPECT_EQ(a.cloud.size(), b.cloud.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < std::min(a.cloud.size(), b.cloud.size()); ++k) {
    worst = std::max(worst, (a.cloud.points[k] - b.cloud.points[k]).norm());
  }
  return worst;
}

TEST(CssTimeFaults, RepeatedOrBackwardRevolutionsAreDroppedAndCountedOutOfOrder) {
  const CssFusionConfig config;
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto revs = truth.revolutions;
  revs.insert(revs.begin() + 5, revs[3]);  // a revolution delivered twice, late
  hal::CssRevolution backwards = revs.back();
  backwards.sequence += 1;
  backwards.stamp -= milliseconds(500);  // new sequence number but a stamp in the past
  revs.push_back(backwards);
  const FusedScan scan = fuse(config, revs, truth.joints);
  EXPECT_EQ(scan.faults.out_of_order, 2u);
  EXPECT_EQ(scan.dropped_frames, 2u);
  EXPECT_EQ(scan.cloud.grid.rows, 20);
}

TEST(CssTimeFaults, JointSampleStampedBeforeItsPredecessorIsDroppedAndCounted) {
  const CssFusionConfig config;
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto joints = truth.joints;
  hal::JointSample stale = joints[40];
  stale.angle_rad += 0.5;  // would wreck every point near it if it were used
  joints.insert(joints.begin() + 60, stale);
  const FusedScan scan = fuse(config, truth.revolutions, joints);
  EXPECT_EQ(scan.faults.out_of_order, 1u);
  EXPECT_LT(max_difference(scan, fuse(config, truth.revolutions, truth.joints)), 1e-9);
}

TEST(CssTimeFaults, LostRevolutionIsCountedAsAGap) {
  const CssFusionConfig config;
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto revs = truth.revolutions;
  revs.erase(revs.begin() + 7);
  const FusedScan scan = fuse(config, revs, truth.joints);
  EXPECT_EQ(scan.faults.gaps, 1u);
  EXPECT_EQ(scan.faults.clock_jumps, 0u);  // the stamp step is two periods, as it should be
  EXPECT_EQ(scan.cloud.grid.rows, 19);
}

TEST(CssTimeFaults, JointStreamGapLongerThanTheLimitIsCounted) {
  const CssFusionConfig config;  // max_reference_gap 50 ms, joint samples every 10 ms
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto joints = truth.joints;
  joints.erase(joints.begin() + 100, joints.begin() + 106);  // 70 ms without a sample
  const FusedScan scan = fuse(config, truth.revolutions, joints);
  EXPECT_EQ(scan.faults.gaps, 1u);
}

TEST(CssTimeFaults, RevolutionsBeyondTheLastJointSampleAreExtrapolatedAndCounted) {
  const CssFusionConfig config;
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto joints = truth.joints;
  // Stop the joint stream inside revolution 17 (of 0..19).
  const hal::Timestamp stop = truth.revolutions[17].stamp + milliseconds(30);
  std::erase_if(joints, [&](const hal::JointSample& j) { return j.stamp > stop; });
  const FusedScan scan = fuse(config, truth.revolutions, joints);
  EXPECT_EQ(scan.faults.extrapolated, 3u);
  ASSERT_EQ(scan.frames.size(), 20u);
  EXPECT_FALSE(scan.frames[16].extrapolated);
  EXPECT_TRUE(scan.frames[17].extrapolated);
  EXPECT_TRUE(scan.frames[19].extrapolated);
}

TEST(CssTimeFaults, RevolutionsWaitingTooLongForTheJointStreamAreFusedExtrapolated) {
  CssFusionConfig config;
  config.limits.max_pending_frames = 2;
  auto truth = make_css_truth(config, CssTruthOptions{});
  CssAssembler assembler(config);
  for (const auto& j : truth.joints) {
    if (j.stamp < truth.revolutions[2].stamp) assembler.add_joint(j);
  }
  for (int r = 0; r < 6; ++r)
    assembler.add_revolution(truth.revolutions[static_cast<std::size_t>(r)]);
  EXPECT_EQ(assembler.pending(), 2u);  // never more than the limit waits
  EXPECT_EQ(assembler.scan().cloud.grid.rows, 4);
  EXPECT_GE(assembler.scan().faults.extrapolated, 2u);
}

TEST(CssTimeFaults, StampStepThatDisagreesWithTheDevicePeriodIsAClockJump) {
  const CssFusionConfig config;  // tolerance 2 ms
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto revs = truth.revolutions;
  for (std::size_t r = 10; r < revs.size(); ++r) revs[r].stamp += milliseconds(8);  // clock stepped
  const FusedScan scan = fuse(config, revs, truth.joints);
  EXPECT_EQ(scan.faults.clock_jumps, 1u);
  EXPECT_EQ(scan.faults.gaps, 0u);
}

TEST(CssTimeFaults, InvalidJointSamplesAreRejectedNotUsed) {
  const CssFusionConfig config;
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto joints = truth.joints;
  joints[50].valid = false;
  joints[50].angle_rad = 3.0;
  const FusedScan scan = fuse(config, truth.revolutions, joints);
  EXPECT_EQ(scan.rejected_reference, 1u);
  EXPECT_EQ(scan.faults.total(), 0u);
  EXPECT_LT(max_difference(scan, fuse(config, truth.revolutions, truth.joints)), 1e-9);
}

TEST(CssTimeFaults, ScanWithMoreFaultsThanTheLimitIsMarkedBadWithTheCounts) {
  CssFusionConfig config;
  config.limits.max_faults = 1;
  auto truth = make_css_truth(config, CssTruthOptions{});
  auto revs = truth.revolutions;
  revs.erase(revs.begin() + 7);  // one gap: within the limit
  EXPECT_FALSE(fuse(config, revs, truth.joints).bad);
  revs.erase(revs.begin() + 12);  // a second gap: past it
  const FusedScan scan = fuse(config, revs, truth.joints);
  EXPECT_TRUE(scan.bad);
  EXPECT_NE(scan.reason.find("gaps 2"), std::string::npos) << scan.reason;
}

}  // namespace css_time_faults_test
}  // namespace rangefit::fusion
