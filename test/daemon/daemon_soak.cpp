// rangefitd under a long stream of requests at full speed: a separate rangefitd process on the
// simulated cell (sim.time_scale = 0, the CSS over the bore plate) answers bore scans, bad
// requests and, when its queue is full, "busy", while this process samples the daemon's resident
// memory, open file descriptors and threads from /proc between blocks of requests. Every request
// must be answered; after the warm-up the descriptors and threads must not move and, over the
// long run, the resident memory must stay within a bound (a result, log or history kept forever
// would grow it by every request).
//
// DaemonSoak.ShortRun (300 requests) is part of the suite. DaemonSoak.TenThousandRequests carries
// the ctest label `soak` and is excluded from the suite and CI: ctest --test-dir build -L soak.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "daemon/dds/client.hpp"
#include "test/daemon/sim_daemon.hpp"

#ifdef RANGEFITD_PATH
namespace rangefit::daemon {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using std::chrono::seconds;

// What /proc says about the daemon at one moment.
struct ProcSample {
  std::size_t answered = 0;
  long rss_kb = -1;   // VmRSS
  long fds = -1;      // entries of /proc/PID/fd
  long threads = -1;  // entries of /proc/PID/task
  double seconds = 0;
};

long count_entries(const fs::path& dir) {
  std::error_code ec;
  long n = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) ++n;
  return ec ? -1 : n;
}

long vm_rss_kb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kb = -1;
      status >> kb;
      return kb;
    }
    status.ignore(4096, '\n');
  }
  return -1;
}

ProcSample sample(pid_t pid, std::size_t answered, Clock::time_point start) {
  const fs::path proc = "/proc/" + std::to_string(pid);
  return {answered, vm_rss_kb(pid), count_entries(proc / "fd"), count_entries(proc / "task"),
          std::chrono::duration<double>(Clock::now() - start).count()};
}

ScanRequest make_request(std::size_t i) { return test::load_request(i, "soak-"); }

struct SoakOptions {
  std::size_t requests = 300;
  std::size_t sample_every = 100;  // answered requests between samples
  std::size_t window = 8;          // requests in flight (the daemon queues 4: the rest is busy)
};

struct SoakReport {
  std::vector<ProcSample> samples;  // the first is taken before any request
  std::size_t answered = 0, found = 0, busy = 0, bad = 0, not_found = 0;
  std::vector<std::string> unanswered, wrong;  // ids; wrong: an answer of the wrong kind
};

// Sends opt.requests requests, at most opt.window unanswered at a time, and takes a sample each
// time opt.sample_every more are answered (with none in flight, so the daemon is idle).
SoakReport soak(test::SimDaemon& daemon, DdsClient& client, const SoakOptions& opt) {
  SoakReport report;
  const auto start = Clock::now();
  report.samples.push_back(sample(daemon.pid(), 0, start));
  std::deque<std::size_t> in_flight;
  auto collect_oldest = [&] {
    const std::size_t i = in_flight.front();
    in_flight.pop_front();
    const ScanRequest req = make_request(i);
    const auto r = client.wait_result(req.id, std::chrono::milliseconds(60000));
    if (!r) {
      report.unanswered.push_back(req.id);
      return;
    }
    ++report.answered;
    const bool busy = r->reason.starts_with("busy");
    const bool bad = r->reason.starts_with("bad request");
    report.busy += busy ? 1 : 0;
    report.bad += bad ? 1 : 0;
    report.found += r->found ? 1 : 0;
    report.not_found += !r->found && !busy && !bad ? 1 : 0;
    const bool expected = test::is_bad(i) ? bad : !bad;
    if (!expected) report.wrong.push_back(req.id + ": " + r->reason);
  };
  for (std::size_t i = 0; i < opt.requests; ++i) {
    while (in_flight.size() >= opt.window) collect_oldest();
    if (!client.send(make_request(i), false)) report.unanswered.push_back(make_request(i).id);
    in_flight.push_back(i);
    if ((i + 1) % opt.sample_every == 0 || i + 1 == opt.requests) {
      while (!in_flight.empty()) collect_oldest();
      report.samples.push_back(sample(daemon.pid(), i + 1, start));
      const ProcSample& s = report.samples.back();
      std::printf("soak: %zu sent, %zu answered, RSS %ld kB, fds %ld, threads %ld, %.1f s\n", i + 1,
                  report.answered, s.rss_kb, s.fds, s.threads, s.seconds);
      std::fflush(stdout);
    }
  }
  return report;
}

// Every request answered with the answer its kind calls for; fds and threads equal at every
// sample from warm_up on (the daemon is idle at each).
void expect_all_answered_and_flat(const SoakReport& report, std::size_t requests,
                                  std::size_t warm_up) {
  std::printf("soak: %zu answered: %zu found, %zu not found, %zu busy, %zu bad request\n",
              report.answered, report.found, report.not_found, report.busy, report.bad);
  EXPECT_EQ(report.answered, requests);
  EXPECT_TRUE(report.unanswered.empty())
      << report.unanswered.size() << " unanswered, first " << report.unanswered.front();
  EXPECT_TRUE(report.wrong.empty())
      << report.wrong.size() << " wrong, first " << report.wrong.front();
  EXPECT_EQ(report.bad, requests / 10 * 3 + (requests % 10 > 6 ? requests % 10 - 6 : 0));
  EXPECT_GT(report.found, 0u) << "no bore found: the soak did not run the detection path";
  const ProcSample* base = nullptr;
  for (const auto& s : report.samples) {
    ASSERT_GT(s.rss_kb, 0) << "no /proc sample";
    if (s.answered < warm_up) continue;
    if (base == nullptr) {
      base = &s;
      continue;
    }
    EXPECT_EQ(s.fds, base->fds) << "open descriptors at " << s.answered << " vs " << base->answered;
    EXPECT_EQ(s.threads, base->threads) << "threads at " << s.answered << " vs " << base->answered;
  }
  ASSERT_NE(base, nullptr);
}

TEST(DaemonSoak, ShortRunAnswersEveryRequestWithDescriptorsAndThreadsFlat) {
  test::SimDaemon daemon("soak_short", {});
  std::optional<DdsClient> client(std::in_place, daemon.domain());
  ASSERT_TRUE(client->wait_for_daemon(seconds(30)));
  SoakOptions opt;
  const SoakReport report = soak(daemon, *client, opt);
  expect_all_answered_and_flat(report, opt.requests, opt.sample_every);
  client.reset();
  EXPECT_EQ(daemon.stop(), 0);
}

// The figures the note reports: RSS at 2,000 and 10,000 answered requests, fds, threads, time.
TEST(DaemonSoak, TenThousandRequestsStayFlatAfterWarmUp) {
  test::SimDaemon daemon("soak_long", {.pictures = true});
  std::optional<DdsClient> client(std::in_place, daemon.domain());
  ASSERT_TRUE(client->wait_for_daemon(seconds(30)));
  SoakOptions opt;
  opt.requests = 10000;
  opt.sample_every = 500;
  const SoakReport report = soak(daemon, *client, opt);
  constexpr std::size_t kWarmUp = 2000;
  expect_all_answered_and_flat(report, opt.requests, kWarmUp);
  const ProcSample* at_warm_up = nullptr;
  for (const auto& s : report.samples) {
    if (at_warm_up == nullptr && s.answered >= kWarmUp) at_warm_up = &s;
  }
  ASSERT_NE(at_warm_up, nullptr);
  const ProcSample& last = report.samples.back();
  std::printf("soak: RSS %ld kB at %zu, %ld kB at %zu: %+ld kB over the last %zu\n",
              at_warm_up->rss_kb, at_warm_up->answered, last.rss_kb, last.answered,
              last.rss_kb - at_warm_up->rss_kb, last.answered - at_warm_up->answered);
  EXPECT_LE(last.rss_kb - at_warm_up->rss_kb, 1024) << "resident memory grows with requests";
  client.reset();
  EXPECT_EQ(daemon.stop(), 0);
}

}  // namespace
}  // namespace rangefit::daemon
#endif
