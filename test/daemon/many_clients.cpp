// Fifty clients at once, each its own DDS participant, send 1,000 requests to a rangefitd process
// on the simulated cell (time_scale 0): bore scans, bad requests and, as a queue of 4 meets 150
// requests in flight, "busy" answers. Mid-run the daemon gets a SIGHUP with a valid configuration
// (queue capacity 6) while requests keep coming: the signal goes once 350 requests are out, in
// the thick of the run (a scan running, the queue full), and no client sends its last request
// before the daemon has confirmed the reload over $NOTIFY_SOCKET.
// Each client counts the answers to its own ids: every id must get exactly one, of its kind.
// (The new queue takes over between scans, so how many "busy" answers name it varies with the
// scans' timing: printed, not checked; dds_delivery_test checks the swap itself.)
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <future>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "daemon/dds/client.hpp"
#include "test/daemon/notify_socket.hpp"
#include "test/daemon/sim_daemon.hpp"

#ifdef RANGEFITD_PATH
namespace rangefit::daemon {
namespace {
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr int kClients = 50;
constexpr std::size_t kPerClient = 20;
constexpr std::size_t kWindow = 3;                          // each client's requests in flight
constexpr std::size_t kSentAtSighup = 350;                  // requests out, of all clients
constexpr std::size_t kHeldUntilReloaded = kPerClient - 1;  // no client sends it before "reloaded"
constexpr std::size_t kCapacityAfterReload = 6;

// What one client saw.
struct Tally {
  bool discovered = false;
  std::map<std::string, int> answers;  // every id it sent: how many answers came
  std::size_t found = 0, busy = 0, busy_after_reload = 0, bad = 0;
  std::vector<std::string> wrong;  // an answer of the wrong kind, or a failed send
};

// What the clients share with the thread that signals the daemon.
struct Gates {
  std::atomic<std::size_t> sent{0};  // by all clients
  std::shared_future<void> reloaded;
};

void run_client(int c, std::uint32_t domain, Gates& gates, Tally& t) {
  DdsClient client(domain);
  t.discovered = client.wait_for_daemon(seconds(60));
  const auto give_up = Clock::now() + seconds(120);  // a bound for a broken daemon, not a goal
  std::map<std::string, std::size_t> index;          // id -> request index
  std::size_t next = 0, open = 0;
  const DdsClient::Callbacks callbacks{.detection = [&](const DetectionResult& r) {
    const auto it = t.answers.find(r.request_id);
    if (it == t.answers.end()) return;  // another client's
    if (++it->second > 1) return;       // a second answer: counted, reported by the test
    --open;
    const bool busy = r.reason.starts_with("busy");
    const bool bad = r.reason.starts_with("bad request");
    t.found += r.found ? 1 : 0;
    t.busy += busy ? 1 : 0;
    t.busy_after_reload +=
        r.reason == "busy: " + std::to_string(kCapacityAfterReload) + " requests queued" ? 1 : 0;
    t.bad += bad ? 1 : 0;
    // The daemon goes on through the reload: no answer may say it stops.
    if (bad != test::is_bad(index[r.request_id]) || r.reason.starts_with("daemon stopping")) {
      t.wrong.push_back(r.request_id + ": " + r.reason);
    }
  }};
  while (t.discovered && (next < kPerClient || open > 0) && Clock::now() < give_up) {
    while (next < kPerClient && open < kWindow) {
      if (next == kHeldUntilReloaded) gates.reloaded.wait();
      const std::size_t i = static_cast<std::size_t>(c) * kPerClient + next;
      const ScanRequest request = test::load_request(i, "client-");
      t.answers.emplace(request.id, 0);
      index[request.id] = i;
      if (!client.send(request, false)) t.wrong.push_back(request.id + ": send failed");
      ++open;
      ++next;
      ++gates.sent;
    }
    client.poll(milliseconds(100), callbacks);
  }
}

TEST(ManyClients, FiftyClientsGetEachOfTheirThousandAnswersAcrossASighupReload) {
  const std::string name = "many_clients";
  test::NotifySocket notify(std::filesystem::temp_directory_path() / (name + "_notify.sock"));
  ASSERT_TRUE(notify.ok());
  test::SimDaemon daemon(name, {.env = {"NOTIFY_SOCKET=" + notify.path().string()}});
  std::promise<void> reloaded;
  Gates gates{.reloaded = reloaded.get_future().share()};
  std::vector<Tally> tallies(kClients);
  std::atomic<int> finished{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&, c] {
      run_client(c, daemon.domain(), gates, tallies[static_cast<std::size_t>(c)]);
      ++finished;
    });
  }
  // This thread plays systemd: it reads every notification (a full socket would block the
  // daemon's sd_notify), sends the SIGHUP once 350 requests are out and releases the clients'
  // last requests when the daemon answers it.
  bool signalled = false, released = false;
  std::string reload_answer;
  const auto give_up = Clock::now() + seconds(180);
  while (finished.load() < kClients && Clock::now() < give_up) {
    const std::string message = notify.next(milliseconds(50));
    if (!signalled && gates.sent.load() >= kSentAtSighup) {
      daemon.write_config(kCapacityAfterReload);
      daemon.signal(SIGHUP);
      signalled = true;
    }
    if (signalled && !released && message.find("reload") != std::string::npos &&
        message.find("RELOADING=1") == std::string::npos) {
      reload_answer = message;
      reloaded.set_value();
      released = true;
    }
  }
  if (!released) reloaded.set_value();  // the clients must not wait forever on a failed test
  for (auto& t : clients) t.join();

  EXPECT_NE(reload_answer.find("STATUS=configuration reloaded"), std::string::npos)
      << "the SIGHUP was answered with: " << reload_answer;
  std::size_t answered = 0, found = 0, busy = 0, busy_after_reload = 0, bad = 0;
  for (int c = 0; c < kClients; ++c) {
    const Tally& t = tallies[static_cast<std::size_t>(c)];
    EXPECT_TRUE(t.discovered) << "client " << c << " found no rangefitd";
    EXPECT_EQ(t.answers.size(), kPerClient) << "client " << c << " sent too few";
    std::size_t mine = 0;
    for (const auto& [id, n] : t.answers) {
      EXPECT_EQ(n, 1) << "client " << c << ": " << n << " answers to " << id;
      mine += n > 0 ? 1 : 0;
    }
    EXPECT_EQ(mine, kPerClient) << "client " << c << " got " << mine << " of its answers";
    EXPECT_TRUE(t.wrong.empty()) << "client " << c << ": " << t.wrong.size()
                                 << " wrong answers, first " << t.wrong.front();
    answered += mine;
    found += t.found;
    busy += t.busy;
    busy_after_reload += t.busy_after_reload;
    bad += t.bad;
  }
  std::printf(
      "many clients: %zu answered: %zu found, %zu busy (%zu with the reloaded queue of %zu), "
      "%zu bad request\n",
      answered, found, busy, busy_after_reload, kCapacityAfterReload, bad);
  EXPECT_EQ(answered, kClients * kPerClient);
  EXPECT_EQ(bad, kClients * kPerClient * 3 / 10);  // the rotation of test::load_kind
  EXPECT_GT(found, 0u) << "no bore found: the run never reached the detection";
  EXPECT_GT(busy, 0u) << "the queue never overflowed";
  EXPECT_EQ(daemon.stop(), 0);
}

}  // namespace
}  // namespace rangefit::daemon
#endif
