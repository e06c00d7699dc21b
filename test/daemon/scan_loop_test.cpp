// The read-fuse-watch loop every scan of rangefitd runs (real and simulated), and the sweep edges
// of a sweep the daemon only watches. The streams are scripted sources (an internal seam): each
// read hands over the next batch of the script, then nothing.
#include "daemon/cell/scan_loop.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rangefit::daemon {
namespace scan_loop_test {

template <class Sample>
class ScriptedSource final : public hal::SampleSource<Sample> {
 public:
  ScriptedSource() = default;
  ScriptedSource(std::initializer_list<std::vector<Sample>> batches) : batches_(batches) {}
  std::string name() const override { return "scripted"; }
  hal::Status start() override { return {}; }
  void stop() override {}
  hal::DeviceHealth health() const override { return {hal::DeviceState::kStreaming, {}, {}, {}}; }
  std::size_t read(std::vector<Sample>& out, hal::Duration) override {
    if (reads_++ >= batches_.size()) return 0;
    const auto& b = batches_[reads_ - 1];
    out.insert(out.end(), b.begin(), b.end());
    return b.size();
  }
  std::size_t reads() const { return reads_; }

 private:
  std::vector<std::vector<Sample>> batches_;
  std::size_t reads_ = 0;
};

struct Loop {
  std::atomic<bool> cancel{false};
  int progress_calls = 0;
  std::function<void()> progress = [this] { ++progress_calls; };
  std::vector<int> fused_paced;
  std::vector<double> fused_drained;
  std::string why;

  // Runs `passes` passes (or until healthy() fails at pass `fail_at`, 1-based; 0 = never).
  ScanLoopEnd run(ScriptedSource<int>& paced, ScriptedSource<double>& drained, int passes,
                  int fail_at = 0) {
    int pass = 0;
    return run_scan_loop(
        paced, drained, {cancel, progress}, [&] { return pass == passes; },
        [&](const std::vector<int>& a, const std::vector<double>& b) {
          ++pass;
          fused_paced.insert(fused_paced.end(), a.begin(), a.end());
          fused_drained.insert(fused_drained.end(), b.begin(), b.end());
        },
        [&](std::string* w) {
          if (pass != fail_at) return true;
          *w = "ranger: link lost";
          return false;
        },
        &why);
  }
};

TEST(ScanLoop, FusesEveryBatchOfBothStreamsAndReportsProgressOnlyWhenDataArrived) {
  ScriptedSource<int> paced{{1, 2}, {}, {3}};
  ScriptedSource<double> drained{{10.0}, {}, {}};
  Loop loop;
  EXPECT_EQ(loop.run(paced, drained, 3), ScanLoopEnd::kDone);
  EXPECT_EQ(loop.fused_paced, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(loop.fused_drained, (std::vector<double>{10.0}));
  EXPECT_EQ(loop.progress_calls, 2) << "the empty second pass reports no progress";
  EXPECT_EQ(paced.reads(), 3u);
  EXPECT_EQ(drained.reads(), 3u);
}

TEST(ScanLoop, AScanThatIsAlreadyDoneReadsNothing) {
  ScriptedSource<int> paced;
  ScriptedSource<double> drained;
  Loop loop;
  EXPECT_EQ(loop.run(paced, drained, 0), ScanLoopEnd::kDone);
  EXPECT_EQ(paced.reads(), 0u);
  EXPECT_EQ(loop.progress_calls, 0);
}

TEST(ScanLoop, CancelEndsTheLoopBeforeTheNextRead) {
  ScriptedSource<int> paced{{1}};
  ScriptedSource<double> drained;
  Loop loop;
  loop.cancel = true;
  EXPECT_EQ(loop.run(paced, drained, 5), ScanLoopEnd::kCancelled);
  EXPECT_EQ(loop.why, "cancelled");
  EXPECT_EQ(paced.reads(), 0u);
  EXPECT_TRUE(loop.fused_paced.empty());
}

TEST(ScanLoop, AnUnhealthyDeviceEndsTheLoopWithItsReasonAfterFusingWhatArrived) {
  ScriptedSource<int> paced{{1}, {2}, {3}};
  ScriptedSource<double> drained;
  Loop loop;
  EXPECT_EQ(loop.run(paced, drained, 3, 2), ScanLoopEnd::kFailed);
  EXPECT_EQ(loop.why, "ranger: link lost");
  EXPECT_EQ(loop.fused_paced, (std::vector<int>{1, 2}));
}

TEST(ScanLoop, EachDrainedStreamsBatchGoesToItsOwnSlotAndAnyArrivalIsProgress) {
  ScriptedSource<int> paced{{}, {}, {7}};
  ScriptedSource<double> a{{1.0}, {}, {}};
  ScriptedSource<double> b{{}, {2.0, 3.0}, {}};
  hal::SampleSource<double>* const drained[] = {&a, &b};
  Loop loop;
  std::vector<std::vector<double>> fused(2);
  int pass = 0;
  const ScanLoopEnd end = run_scan_loop(
      paced, std::span<hal::SampleSource<double>* const>(drained), {loop.cancel, loop.progress},
      [&] { return pass == 3; },
      [&](const std::vector<int>&, std::span<const std::vector<double>> batches) {
        ++pass;
        ASSERT_EQ(batches.size(), 2u);
        for (std::size_t k = 0; k < 2; ++k) {
          fused[k].insert(fused[k].end(), batches[k].begin(), batches[k].end());
        }
      },
      [](std::string*) { return true; }, &loop.why);
  EXPECT_EQ(end, ScanLoopEnd::kDone);
  EXPECT_EQ(fused[0], (std::vector<double>{1.0}));
  EXPECT_EQ(fused[1], (std::vector<double>{2.0, 3.0}));
  EXPECT_EQ(loop.progress_calls, 3) << "a profile of either camera or an axis sample is progress";
}

TEST(SweepEdges, EndsOnlyAtPlusHalfAfterMinusHalfWasReached) {
  SweepEdges sweep{0.1};
  for (double a : {0.0, 0.1, 0.05}) sweep.see(a);  // +half before the start: not the end
  EXPECT_FALSE(sweep.at_start);
  EXPECT_FALSE(sweep.at_end);
  for (double a : {-0.05, -0.1, 0.0}) sweep.see(a);
  EXPECT_TRUE(sweep.at_start);
  EXPECT_FALSE(sweep.at_end);
  sweep.see(0.09995);  // within the 1e-4 rad slack
  EXPECT_TRUE(sweep.at_end);
}

TEST(SweepEdges, NoAnglesMeanNoSweep) {
  const SweepEdges sweep{0.1};
  EXPECT_FALSE(sweep.at_start);
  EXPECT_FALSE(sweep.at_end);
}

TEST(FinishScan, PlacesTheCloudWithTheExtrinsicsAfterTheMountAndNamesTheDeviceOnAFusionError) {
  DeviceConfig d;
  d.name = "css";
  d.xyz_mm = {10, 0, 0};
  d.rpy_rad = {0, 0, M_PI / 2};  // yaw 90 deg
  fusion::FusedScan scan;
  scan.cloud.points.emplace_back(1, 2, 3);
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.translation() = Eigen::Vector3d(0, 5, 0);
  const ScanOutcome out = finish_scan(d, scan, mount);
  ASSERT_TRUE(out.status) << out.status.message;
  // (1, 2, 3) + mount (0, 5, 0) = (1, 7, 3); yawed (-7, 1, 3); + (10, 0, 0).
  EXPECT_TRUE(out.cloud.points.at(0).isApprox(Eigen::Vector3d(3, 1, 3)))
      << out.cloud.points.at(0).transpose();
  scan.bad = true;
  scan.reason = "too many faults";
  EXPECT_EQ(finish_scan(d, scan).status.message, "css: fusion: too many faults");
}

}  // namespace scan_loop_test
}  // namespace rangefit::daemon
