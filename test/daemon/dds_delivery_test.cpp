// Every request gets exactly one answer and its client sees it: quick answers ("bad request",
// "busy") in bursts, many clients at once, and a SIGHUP reload while a scan runs. Loopback DDS,
// the service in-process with a fake backend whose scan the test can hold.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "daemon/dds/client.hpp"
#include "daemon/rangefitd/service.hpp"
#include "test/daemon/fakes.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace dds_delivery_test {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

ScanRequest bore(const std::string& id, double radius_mm = 5) {
  ScanRequest r;
  r.id = id;
  r.kind = DetectKind::kBore;
  r.bore.radius_mm = radius_mm;
  return r;
}

// Collects the answers to ids within one overall deadline; the ids that got none are returned.
std::vector<std::string> unanswered(DdsClient& client, const std::vector<std::string>& ids,
                                    seconds budget, std::vector<DetectionResult>* results) {
  const auto deadline = Clock::now() + budget;
  std::vector<std::string> missing;
  for (const auto& id : ids) {
    const auto left = std::chrono::duration_cast<milliseconds>(deadline - Clock::now());
    auto r = client.wait_result(id, std::max(left, milliseconds(1)));
    if (!r) {
      missing.push_back(id);
    } else if (results != nullptr) {
      results->push_back(std::move(*r));
    }
  }
  return missing;
}

class DdsDeliveryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_dir(fs::path("rangefit_dds_delivery_test") /
                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
    config_ = test::replay_css_config(dir_, dir_ / "scan.ply");
    config_.dds.diagnostics_period_s = 0.2;
  }
  void TearDown() override {
    loop_.reset();
    service_.reset();
    fs::remove_all(dir_);
  }
  test::FakeBackend* start() {
    auto backend = std::make_unique<test::FakeBackend>();
    test::FakeBackend* raw = backend.get();
    service_ = std::make_unique<Service>(config_, clock_, std::move(backend),
                                         std::make_unique<test::CentroidDetector>());
    loop_ = std::make_unique<test::ServiceLoop>(*service_);
    return raw;
  }

  fs::path dir_;
  DaemonConfig config_;
  hal::MonotonicClock clock_;
  std::unique_ptr<Service> service_;
  std::unique_ptr<test::ServiceLoop> loop_;
};

TEST_F(DdsDeliveryTest, EveryOneOfThreeHundredBadRequestsSentInABurstIsAnswered) {
  start();
  DdsClient client(config_.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(seconds(20)));
  std::vector<std::string> ids;
  for (int i = 0; i < 300; ++i) {
    ids.push_back("bad-" + std::to_string(i));
    ASSERT_TRUE(client.send(bore(ids.back(), 0.0), false));  // radius 0: "bad request"
  }
  std::vector<DetectionResult> results;
  const auto missing = unanswered(client, ids, seconds(30), &results);
  EXPECT_TRUE(missing.empty()) << missing.size() << " of 300 unanswered, first " << missing[0];
  for (const auto& r : results) EXPECT_EQ(r.reason.rfind("bad request: ", 0), 0u) << r.reason;
}

// Each client has its own participant, discovers the daemon by itself and sends at once; the
// queue (capacity 4) overflows, so most answers are "busy", some bad, some real results.
TEST_F(DdsDeliveryTest, EightyConcurrentClientsEachGetTheirOneAnswer) {
  test::FakeBackend* backend = start();
  backend->points = 50;
  constexpr int kClients = 80;
  std::atomic<int> answered{0}, no_daemon{0}, busy{0}, found{0}, bad{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&, c] {
      DdsClient client(config_.dds.domain_id);
      if (!client.wait_for_daemon(seconds(30))) {
        ++no_daemon;
        return;
      }
      const std::string id = "client-" + std::to_string(c);
      if (!client.send(bore(id, c % 5 == 0 ? 0.0 : 5.0), false)) return;
      const auto r = client.wait_result(id, seconds(30));
      if (!r) return;
      ++answered;
      if (r->found) ++found;
      if (r->reason.rfind("busy", 0) == 0) ++busy;
      if (r->reason.rfind("bad request", 0) == 0) ++bad;
    });
  }
  for (auto& t : clients) t.join();
  EXPECT_EQ(no_daemon.load(), 0);
  EXPECT_EQ(answered.load(), kClients);
  EXPECT_EQ(bad.load(), kClients / 5);
  EXPECT_EQ(found.load() + busy.load() + bad.load(), kClients);
  EXPECT_GT(found.load(), 0);
}

// A client whose result reader starts only after its requests went out (a slow subscriber,
// or one whose reader is matched by the daemon later than its writer): quick "bad request"
// answers must wait for that reader instead of being written into the gap, where transient-local
// would hand the reader only the last of them.
TEST_F(DdsDeliveryTest, AnswersReachAClientWhoseResultReaderStartsAfterItsRequests) {
  start();
  dds::Participant participant(config_.dds.domain_id);
  topics::Writer<topics::Request> requests(participant, topics::request(64));
  const auto deadline = Clock::now() + seconds(20);
  while (requests.matched() == 0 && Clock::now() < deadline) {
    std::this_thread::sleep_for(milliseconds(5));
  }
  ASSERT_GT(requests.matched(), 0) << "the daemon's request reader was not discovered";
  constexpr int kRequests = 10;
  for (int i = 0; i < kRequests; ++i) {
    const RequestOut out(bore("early-" + std::to_string(i), 0.0), false);  // "bad request"
    ASSERT_TRUE(requests.write(out.msg()));
  }
  std::this_thread::sleep_for(milliseconds(100));  // the daemon has taken and answered them
  topics::Reader<topics::Detections> results(participant, topics::detections_reader());
  std::set<std::string> answered;
  const auto until = Clock::now() + seconds(10);
  while (answered.size() < kRequests && Clock::now() < until) {
    results.wait(milliseconds(100));
    results.take_each([&](const rangefit_msgs_msg_dds__Detection_& m) {
      const DetectionResult r = from_msg(m);
      EXPECT_EQ(r.reason.rfind("bad request: ", 0), 0u) << r.reason;
      answered.insert(r.request_id);
    });
  }
  EXPECT_EQ(answered.size(), static_cast<std::size_t>(kRequests))
      << "answers written before the client's result reader was matched were lost";
}

// rangefitd's main loop on one thread: steps the service and, when asked, reloads on the same
// thread (as SIGHUP does), recording when the reload returned.
class ReloadingLoop {
 public:
  ReloadingLoop(Service& service, DaemonConfig next)
      : next_(std::move(next)), thread_([this, &service] {
          while (running_) {
            service.step(milliseconds(20));
            if (reload_asked_.exchange(false)) {
              std::string why;
              reload_ok_ = service.reload(next_, &why);
              reload_done_ = true;
            }
          }
        }) {}
  ~ReloadingLoop() {
    running_ = false;
    thread_.join();
  }
  void ask_reload() { reload_asked_ = true; }
  bool wait_reload_done(milliseconds limit) const {
    const auto deadline = Clock::now() + limit;
    while (!reload_done_ && Clock::now() < deadline) std::this_thread::sleep_for(milliseconds(5));
    return reload_done_;
  }
  bool reload_ok() const { return reload_ok_; }

 private:
  DaemonConfig next_;
  std::atomic<bool> running_{true}, reload_asked_{false}, reload_done_{false}, reload_ok_{false};
  std::thread thread_;
};

TEST_F(DdsDeliveryTest, ReloadDuringAScanAnswersEveryQueuedAndLaterRequestWithItsResult) {
  auto backend_owner = std::make_unique<test::FakeBackend>();
  test::FakeBackend* backend = backend_owner.get();
  backend->hang = true;  // the first scan runs until the test releases it
  service_ = std::make_unique<Service>(config_, clock_, std::move(backend_owner),
                                       std::make_unique<test::CentroidDetector>());
  DaemonConfig next = config_;
  next.service.queue_capacity = 7;
  ReloadingLoop loop(*service_, next);

  DdsClient client(config_.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(seconds(20)));
  std::vector<std::string> ids;
  auto send = [&](const std::string& id) {
    ids.push_back(id);
    ASSERT_TRUE(client.send(bore(id), false));
  };
  send("running");
  for (int i = 0; i < 200 && backend->scans.load() == 0; ++i)
    std::this_thread::sleep_for(milliseconds(10));
  ASSERT_EQ(backend->scans.load(), 1);
  send("queued-1");
  send("queued-2");
  std::this_thread::sleep_for(milliseconds(200));  // both taken into the queue
  loop.ask_reload();
  // The reload must not wait for the scan: the main loop keeps taking requests meanwhile.
  const bool returned_during_scan = loop.wait_reload_done(seconds(3));
  send("during-1");
  send("during-2");
  std::this_thread::sleep_for(milliseconds(200));
  backend->release = true;
  EXPECT_TRUE(returned_during_scan);
  ASSERT_TRUE(loop.wait_reload_done(seconds(20)));
  EXPECT_TRUE(loop.reload_ok());

  std::vector<DetectionResult> results;
  const auto missing = unanswered(client, ids, seconds(30), &results);
  EXPECT_TRUE(missing.empty()) << missing.size() << " unanswered, first " << missing[0];
  for (const auto& r : results) EXPECT_TRUE(r.found) << r.request_id << ": " << r.reason;
  // The new configuration is in force once the scan that ran during the reload is done.
  for (int i = 0; i < 100 && service_->config().service.queue_capacity != 7u; ++i) {
    std::this_thread::sleep_for(milliseconds(20));
  }
  EXPECT_EQ(service_->config().service.queue_capacity, 7u);
}

}  // namespace dds_delivery_test
}  // namespace rangefit::daemon
