#include "daemon/service/pipeline.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "test/daemon/fakes.hpp"

namespace rangefit::daemon {
namespace pipeline_test {

using test::CentroidDetector;
using test::FakeBackend;
using test::ManualClock;
using test::RecordingSink;
using test::request;

TEST(Pipeline, AnswersEachRequestWithTheDetectorsResultAndTheWholeCloud) {
  FakeBackend backend;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, nullptr, sink, clock);
  ASSERT_EQ(p.submit(request("a")), Submit::kAccepted);
  ASSERT_TRUE(sink.wait_results(1));
  const auto r = sink.results_copy().at(0);
  EXPECT_EQ(r.request_id, "a");
  EXPECT_TRUE(r.found);
  EXPECT_EQ(r.num_points, 100u);
  ASSERT_EQ(sink.clouds.size(), 1u);
  EXPECT_EQ(sink.clouds[0], 100u);
}

TEST(Pipeline, EmptyScanGivesANotFoundResultNotACrash) {
  FakeBackend backend;
  backend.points = 0;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, nullptr, sink, clock);
  p.submit(request("empty"));
  ASSERT_TRUE(sink.wait_results(1));
  EXPECT_FALSE(sink.results_copy()[0].found);
  EXPECT_EQ(sink.results_copy()[0].reason, "empty cloud");
}

TEST(Pipeline, FullQueueAnswersBusyInsteadOfDropping) {
  FakeBackend backend;
  backend.hang = true;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({2}, backend, detector, nullptr, sink, clock);
  ASSERT_EQ(p.submit(request("running")), Submit::kAccepted);
  while (backend.scans == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(p.submit(request("q1")), Submit::kAccepted);
  EXPECT_EQ(p.submit(request("q2")), Submit::kAccepted);
  EXPECT_EQ(p.submit(request("q3")), Submit::kBusy);
  EXPECT_EQ(p.rejected_busy(), 1u);
  backend.release = true;
  ASSERT_TRUE(sink.wait_results(3));
  for (const auto& r : sink.results_copy()) EXPECT_TRUE(r.found) << r.request_id;
}

TEST(Pipeline, DeviceGoneMidScanGivesAnErrorResultThenRecovers) {
  FakeBackend backend;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, nullptr, sink, clock);
  backend.present = false;
  p.submit(request("lost"));
  ASSERT_TRUE(sink.wait_results(1));
  EXPECT_FALSE(sink.results_copy()[0].found);
  EXPECT_NE(sink.results_copy()[0].reason.find("device disappeared"), std::string::npos);
  EXPECT_EQ(p.state(), LifecycleState::kFault);
  EXPECT_NE(p.last_error().find("device disappeared"), std::string::npos);

  backend.present = true;
  p.submit(request("back"));
  ASSERT_TRUE(sink.wait_results(2));
  EXPECT_TRUE(sink.results_copy()[1].found);
  EXPECT_EQ(p.state(), LifecycleState::kIdle);
}

TEST(Pipeline, DetectorExceptionBecomesAnErrorResult) {
  FakeBackend backend;
  CentroidDetector detector;
  detector.throw_next = true;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, nullptr, sink, clock);
  p.submit(request("x"));
  ASSERT_TRUE(sink.wait_results(1));
  EXPECT_EQ(sink.results_copy()[0].reason, "detector threw: boom");
}

TEST(Pipeline, HungScanStopsProgressSoTheWatchdogStarves) {
  FakeBackend backend;
  backend.hang = true;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, nullptr, sink, clock);
  const hal::Duration limit = std::chrono::seconds(30);
  EXPECT_FALSE(p.stalled(clock.now(), limit));
  p.submit(request("hang"));
  while (backend.scans == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  clock.advance(std::chrono::seconds(31));
  EXPECT_TRUE(p.stalled(clock.now(), limit));
  p.stop(/*abort=*/true);  // SIGTERM path: the hung scan is cancelled and answered
  ASSERT_TRUE(sink.wait_results(1));
  EXPECT_NE(sink.results_copy()[0].reason.find("cancelled"), std::string::npos);
}

TEST(Pipeline, IdlePipelineKeepsMakingProgress) {
  FakeBackend backend;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, nullptr, sink, clock);
  clock.advance(std::chrono::seconds(31));
  // The idle worker wakes every 100 ms and stamps the (advanced) clock.
  while (p.stalled(clock.now(), std::chrono::seconds(30))) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  SUCCEED();
}

TEST(Pipeline, SpoolsTheCloudAndResultBeforePublishing) {
  const auto dir = std::filesystem::temp_directory_path() / "rangefit_pipeline_spool_test";
  std::filesystem::remove_all(dir);
  Spool spool({dir, 1ull << 30, 24.0});
  std::string why;
  ASSERT_TRUE(spool.open(&why)) << why;
  FakeBackend backend;
  CentroidDetector detector;
  RecordingSink sink;
  ManualClock clock;
  Pipeline p({4}, backend, detector, &spool, sink, clock);
  p.submit(request("spooled"));
  ASSERT_TRUE(sink.wait_results(1));
  const auto r = sink.results_copy()[0];
  ASSERT_FALSE(r.spool_entry.empty());
  const auto entry = read_spool_entry(r.spool_entry, &why);
  ASSERT_TRUE(entry) << why;
  EXPECT_EQ(entry->cloud.size(), 100u);
  EXPECT_EQ(entry->result.request_id, "spooled");
  EXPECT_TRUE(entry->result.found);
  std::filesystem::remove_all(dir);
}

}  // namespace pipeline_test
}  // namespace rangefit::daemon
