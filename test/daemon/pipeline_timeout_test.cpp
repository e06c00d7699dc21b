// service.scan_timeout_s and detection.timeout_s: an overlong scan or detection is answered with
// an error result and the daemon goes on with the next request.
#include <gtest/gtest.h>

#include "daemon/service/pipeline.hpp"
#include "test/daemon/fakes.hpp"

namespace rangefit::daemon {
namespace pipeline_timeout_test {

using std::chrono::milliseconds;
using test::CentroidDetector;
using test::FakeBackend;
using test::ManualClock;
using test::RecordingSink;
using test::request;

// A detector that does not return until released (detect/ cannot be interrupted).
class BlockingDetector final : public Detector {
 public:
  std::atomic<bool> block{true};
  std::atomic<int> calls{0};
  DetectionResult detect(const PointCloud& cloud, const ScanRequest& r, const ScanSensor&,
                         std::span<const SensorScan>) override {
    ++calls;
    while (block) std::this_thread::sleep_for(milliseconds(1));
    return inner_.detect(cloud, r, {}, {});
  }

 private:
  CentroidDetector inner_;
};

TEST(PipelineTimeouts, OverlongScanIsAnsweredScanTimeoutAndTheNextRequestRuns) {
  FakeBackend backend;
  backend.hang = true;  // makes no progress until cancelled
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  PipelineOptions options;
  options.scan_timeout = milliseconds(50);
  Pipeline p(options, backend, detector, nullptr, sink, clock);
  p.submit(request("slow"));
  ASSERT_TRUE(sink.wait_results(1));
  const auto first = sink.results_copy()[0];
  EXPECT_FALSE(first.found);
  EXPECT_EQ(first.reason.rfind("scan timeout", 0), 0u) << first.reason;
  EXPECT_EQ(first.num_points, 0u);
  EXPECT_EQ(p.state(), LifecycleState::kFault);

  backend.hang = false;
  p.submit(request("quick"));
  ASSERT_TRUE(sink.wait_results(2));
  EXPECT_TRUE(sink.results_copy()[1].found) << sink.results_copy()[1].reason;
  EXPECT_EQ(p.state(), LifecycleState::kIdle);
}

TEST(PipelineTimeouts, WithoutALimitAScanIsNeverCutShort) {
  FakeBackend backend;
  backend.hang = true;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, nullptr, sink, clock);  // scan_timeout 0: no limit
  p.submit(request("long"));
  while (backend.scans == 0) std::this_thread::sleep_for(milliseconds(1));
  std::this_thread::sleep_for(milliseconds(100));
  EXPECT_TRUE(sink.results_copy().empty());
  backend.release = true;
  ASSERT_TRUE(sink.wait_results(1));
  EXPECT_TRUE(sink.results_copy()[0].found);
}

TEST(PipelineTimeouts, OverlongDetectionIsAnsweredAtOnceAndStarvesTheWatchdogUntilItReturns) {
  FakeBackend backend;
  BlockingDetector detector;
  RecordingSink sink;
  ManualClock clock;
  PipelineOptions options;
  options.detect_timeout = milliseconds(50);
  Pipeline p(options, backend, detector, nullptr, sink, clock);
  p.submit(request("stuck"));
  ASSERT_TRUE(sink.wait_results(1));  // answered while the detector still runs
  const auto first = sink.results_copy()[0];
  EXPECT_FALSE(first.found);
  EXPECT_EQ(first.reason.rfind("detection timeout", 0), 0u) << first.reason;
  EXPECT_EQ(p.state(), LifecycleState::kFault);

  // The worker waits for the stuck detector without stamping progress: the watchdog starves.
  p.submit(request("next"));
  clock.advance(std::chrono::seconds(31));
  std::this_thread::sleep_for(milliseconds(250));  // a healthy worker would stamp within 100 ms
  EXPECT_TRUE(p.stalled(clock.now(), std::chrono::seconds(30)));
  EXPECT_EQ(detector.calls, 1);

  detector.block = false;  // the detector returns: the queued request runs
  ASSERT_TRUE(sink.wait_results(2));
  EXPECT_EQ(sink.results_copy()[1].request_id, "next");
  EXPECT_TRUE(sink.results_copy()[1].found);
  EXPECT_FALSE(p.stalled(clock.now(), std::chrono::seconds(30)));
}

}  // namespace pipeline_timeout_test
}  // namespace rangefit::daemon
