// rangefitd's HTTP and TCP interfaces end to end: a rangefitd process on the simulated cell (CSS
// over the bore plate, stripe cell over the table-top scene of thesis fig. 5.18) answers over
// loopback what robot programs and careless or hostile clients send; the daemon never dies.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <future>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "web_daemon.hpp"

namespace rangefit::test {
namespace interfaces_test {
using nlohmann::json;

// The 12 mm bore the plate puts under the CSS; CAD prior 0.8 mm off the true entrance.
const json kBore = {
    {"kind", "bore"},
    {"bore", {{"position_mm", {0.8, -0.5, 285.8}}, {"axis", {0, 0, 1}}, {"radius_mm", 6}}}};

json parse(const httplib::Result& r) { return r ? json::parse(r->body, nullptr, false) : json(); }

// A raw TCP connection to the line interface.
class Tcp {
 public:
  explicit Tcp(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~Tcp() { ::close(fd_); }
  bool connected() const { return connected_; }
  void send(const std::string& text) { ::send(fd_, text.data(), text.size(), MSG_NOSIGNAL); }
  json answer(int timeout_ms = 60000) {
    while (buffer_.find('\n') == std::string::npos) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, timeout_ms) != 1) return {};
      char chunk[4096];
      const ssize_t n = ::recv(fd_, chunk, sizeof chunk, 0);
      if (n <= 0) return {};
      buffer_.append(chunk, static_cast<std::size_t>(n));
    }
    const auto end = buffer_.find('\n');
    const json j = json::parse(buffer_.substr(0, end), nullptr, false);
    buffer_.erase(0, end + 1);
    return j;
  }

 private:
  int fd_;
  bool connected_ = false;
  std::string buffer_;
};

TEST(Interfaces, HttpAndTcpRequestsAreScannedDetectedAndServedWithTheirFiles) {
  WebDaemon daemon("requests", "");
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  auto c = daemon.client();
  const auto r = c.Post("/v1/detect", kBore.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json bore = parse(r);
  EXPECT_EQ(bore["status"], "ok");
  ASSERT_TRUE(bore["found"].get<bool>()) << bore;
  EXPECT_NEAR(bore["bore_radius_mm"].get<double>(), 6.0, 0.1);
  const json entrance = bore["parts"][0]["translation_mm"];
  EXPECT_NEAR(entrance[2].get<double>(), 285.8, 0.3);
  const std::string id = bore["request_id"];

  // Read without the token: the result, its files, the state.
  auto reader = daemon.client(false);
  EXPECT_EQ(parse(reader.Get("/v1/results/" + id))["request_id"], id);
  const auto png = reader.Get("/v1/results/" + id + "/picture.png");
  ASSERT_TRUE(png);
  ASSERT_EQ(png->status, 200);
  EXPECT_EQ(png->body.substr(1, 3), "PNG");
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  const auto ply = reader.Get("/v1/results/" + id + "/cloud.ply");
  ASSERT_TRUE(ply);
  EXPECT_EQ(ply->body.substr(0, 4), "ply\n");
  EXPECT_GT(ply->body.size(), 1000u * 24);
  const json state = parse(reader.Get("/v1/state"));
  EXPECT_EQ(state["state"], "idle");
  EXPECT_EQ(state["completed"], 1);
  EXPECT_FALSE(state["diagnostics"].empty());
  EXPECT_EQ(state["models"], json::array({"sphere"}));
  // Nothing outside the spool, nothing but the two files.
  EXPECT_EQ(reader.Get("/v1/results/" + id + "/request.json")->status, 404);
  EXPECT_EQ(reader.Get("/v1/results/../../../etc/passwd")->status, 404);
  EXPECT_EQ(reader.Get("/v1/results/nope/cloud.ply")->status, 404);

  // The object request over the line interface: the sphere of fig. 5.18 at (160, 65, 50) mm.
  Tcp tcp(daemon.tcp_port());
  ASSERT_TRUE(tcp.connected());
  tcp.send(json{{"op", "detect"},
                {"request", {{"kind", "object"}, {"model", "sphere"}, {"id", "o1"}}},
                {"token", kToken}}
               .dump() +
           "\n");
  const json object = tcp.answer(240000);
  ASSERT_EQ(object["status"], "ok") << object;
  ASSERT_TRUE(object["found"].get<bool>()) << object;
  const json centre = object["parts"][0]["translation_mm"];
  EXPECT_NEAR(centre[0].get<double>(), 160, 2);
  EXPECT_NEAR(centre[1].get<double>(), 65, 2);
  EXPECT_NEAR(centre[2].get<double>(), 50, 2);
  EXPECT_DOUBLE_EQ(object["shapes"]["sphere"]["a1"].get<double>(), 50.0);
  // Both results are listed, newest first.
  const json recent = parse(reader.Get("/v1/results?n=5"));
  ASSERT_EQ(recent["results"].size(), 2u);
  EXPECT_EQ(recent["results"][0]["request_id"], "o1");
  EXPECT_EQ(daemon.stop(), 0);
}

TEST(Interfaces, BadHugeSlowAndManyClientsAreAnsweredAndTheDaemonLives) {
  WebDaemon daemon("hostile", "queue_capacity = 2");
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  auto c = daemon.client();
  for (const std::string bad : {"{ not json", "[1, 2]", "", R"({"kind": "screw"})",
                                R"({"kind": "bore", "bore": {"radius_mm": "six"}})",
                                R"({"kind": "bore", "bore": {"radius_mm": -1}})",
                                R"({"kind": "bore", "id": "../../etc", "bore": {"radius_mm": 6}})",
                                R"({"kind": "object", "model": "unicorn"})"}) {
    const auto r = c.Post("/v1/detect", bad, "application/json");
    ASSERT_TRUE(r) << bad;
    EXPECT_EQ(r->status, 400) << bad << " -> " << r->body;
    EXPECT_EQ(parse(r)["status"], "bad_request") << bad;
    EXPECT_FALSE(parse(r)["error"].get<std::string>().empty()) << bad;
  }
  // Over [http] max_request_bytes (4096): refused unread.
  const auto huge = c.Post("/v1/detect", std::string(1 << 20, '{'), "application/json");
  ASSERT_TRUE(huge);
  EXPECT_EQ(huge->status, 413);
  // No token: read-only.
  EXPECT_EQ(daemon.client(false).Post("/v1/detect", kBore.dump(), "application/json")->status, 403);

  // A slow client sends half a request and stalls; it holds one thread, the others serve.
  Tcp slow_http(daemon.http_port());
  slow_http.send("POST /v1/detect HTTP/1.1\r\nHost: x\r\nContent-Length: 400\r\n\r\n{\"kind\"");
  Tcp slow_line(daemon.tcp_port());
  slow_line.send(R"({"op": "sta)");

  // 50 clients at once, half reading the state, half asking for a bore scan: every one gets an
  // answer, the scans a result or busy (the queue holds two behind the running one).
  std::vector<std::future<int>> answers;
  for (int i = 0; i < 50; ++i) {
    answers.push_back(std::async(std::launch::async, [&daemon, i] {
      auto client = daemon.client();
      const auto r = i % 2 ? client.Get("/v1/state")
                           : client.Post("/v1/detect?wait=0", kBore.dump(), "application/json");
      return r ? r->status : -1;
    }));
  }
  int ok = 0, accepted = 0, busy = 0;
  for (auto& a : answers) {
    const int code = a.get();
    ok += code == 200;
    accepted += code == 202;
    busy += code == 503;
    EXPECT_TRUE(code == 200 || code == 202 || code == 503) << code;
  }
  EXPECT_EQ(ok, 25);
  EXPECT_GE(accepted, 1);
  EXPECT_EQ(accepted + busy, 25);

  // The line interface: bad JSON keeps the connection, an overlong line closes it.
  Tcp tcp(daemon.tcp_port());
  tcp.send("{oops\n" + json{{"op", "state"}}.dump() + "\n");
  EXPECT_EQ(tcp.answer()["status"], "bad_request");
  EXPECT_EQ(tcp.answer()["status"], "ok");
  tcp.send(std::string(100000, ' ') + "x\n");  // over [tcp] max_request_bytes (64 KiB)
  EXPECT_EQ(tcp.answer()["status"], "too_large");

  EXPECT_TRUE(daemon.alive());
  EXPECT_EQ(parse(daemon.client(false).Get("/v1/state"))["status"], "ok");
  EXPECT_EQ(daemon.stop(), 0) << daemon.log();
}

// A cell that is busy: CSS scans at the real pace over a sweep that outlasts the scan timeout.
TEST(Interfaces, ABusyCellAnswersBusyAndATimedOutScanTimeoutOnEveryInterface) {
  WebDaemon daemon("busy", "queue_capacity = 1\nscan_timeout_s = 1.0", 1.0);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  json slow = kBore;
  slow["sweep"] = {-0.03, 0.03, 0.02};  // rad, rad/s: 3 s at the real pace
  auto c = daemon.client();
  slow["id"] = "running";
  const auto first = c.Post("/v1/detect?wait=0", slow.dump(), "application/json");
  ASSERT_EQ(first->status, 202) << first->body;
  // The queue holds one: the second request is queued only once the first has left it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (parse(c.Get("/v1/state"))["state"] != "scanning" &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  slow["id"] = "queued";
  ASSERT_EQ(c.Post("/v1/detect?wait=0", slow.dump(), "application/json")->status, 202);
  slow["id"] = "refused";
  const auto busy = c.Post("/v1/detect", slow.dump(), "application/json");
  ASSERT_TRUE(busy);
  EXPECT_EQ(busy->status, 503);
  EXPECT_EQ(busy->get_header_value("Retry-After"), "1");
  const json busy_body = parse(busy);
  EXPECT_EQ(busy_body["status"], "busy");
  EXPECT_TRUE(busy_body["error"].get<std::string>().starts_with("busy: ")) << busy_body;
  // The same answer on the line interface, and the same result a DDS subscriber got.
  Tcp tcp(daemon.tcp_port());
  slow["id"] = "refused-too";
  slow["token"] = kToken;
  tcp.send(slow.dump() + "\n");
  const json line_busy = tcp.answer();
  EXPECT_EQ(line_busy["status"], "busy");
  EXPECT_EQ(line_busy["error"], busy_body["error"]);
  EXPECT_EQ(parse(c.Get("/v1/results/refused"))["reason"], busy_body["error"]);

  // The running scan outlasts scan_timeout_s: the waiter hears timeout (504), as DDS does.
  tcp.send(json{{"op", "result"}, {"id", "running"}}.dump() + "\n");
  EXPECT_EQ(tcp.answer()["status"], "accepted");
  json timed_out;
  for (int i = 0; i < 200 && !timed_out.contains("reason"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const auto r = c.Get("/v1/results/running");
    if (r && r->status != 202) {
      EXPECT_EQ(r->status, 504) << r->body;
      timed_out = parse(r);
    }
  }
  EXPECT_EQ(timed_out["status"], "timeout");
  EXPECT_TRUE(timed_out["reason"].get<std::string>().starts_with("scan timeout")) << timed_out;
  EXPECT_TRUE(daemon.alive());
  EXPECT_EQ(daemon.stop(), 0) << daemon.log();
}

// Waiting clients hold a server thread each: more of them than the server has threads, while
// the cell is busy scanning. Those over the bound hear busy at once, the state answers all the
// while, and every waiter gets its result or a clear error (here: the slow scans time out).
TEST(Interfaces, MoreWaitingClientsThanServerThreadsLeaveTheStateAnswering) {
  // queue_capacity 1: two may wait (the running scan and the queued one), 2 + 8 threads.
  WebDaemon daemon("waiters", "queue_capacity = 1\nscan_timeout_s = 1.0", 1.0);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  json slow = kBore;
  slow["sweep"] = {-0.03, 0.03, 0.02};  // 3 s at the real pace: outlasts scan_timeout_s
  const int clients = 14;
  std::vector<std::future<httplib::Result>> waiters;
  for (int i = 0; i < clients; ++i) {
    slow["id"] = std::string("waiter-").append(std::to_string(i));
    waiters.push_back(std::async(std::launch::async, [&daemon, request = slow.dump()] {
      return daemon.client().Post("/v1/detect", request, "application/json");
    }));
  }
  // While they wait (or are answered), the state answers every time it is asked.
  int states = 0, states_while_waiting = 0;
  for (bool waiting = true; waiting;) {
    waiting = false;
    for (auto& w : waiters) {
      waiting = waiting || w.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
    }
    auto reader = daemon.client(false);
    reader.set_read_timeout(10, 0);
    const auto state = reader.Get("/v1/state");
    ASSERT_TRUE(state) << "GET /v1/state got no answer while clients waited";
    EXPECT_EQ(state->status, 200) << state->body;
    ++states;
    states_while_waiting += waiting;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_GT(states_while_waiting, 0);
  int busy = 0, timed_out = 0;
  for (auto& w : waiters) {
    const httplib::Result r = w.get();
    ASSERT_TRUE(r) << "a waiting client got no answer";
    const json body = parse(r);
    if (r->status == 503) {
      ++busy;
      EXPECT_EQ(body["status"], "busy") << r->body;
      EXPECT_EQ(r->get_header_value("Retry-After"), "1");
    } else {
      EXPECT_EQ(r->status, 504) << r->body;
      EXPECT_EQ(body["status"], "timeout") << r->body;
      ++timed_out;
    }
    EXPECT_FALSE(body.value("error", std::string()).empty()) << r->body;
  }
  EXPECT_EQ(busy + timed_out, clients);
  EXPECT_GE(busy, clients - 2);
  EXPECT_GE(timed_out, 1);
  EXPECT_TRUE(daemon.alive());
  EXPECT_EQ(daemon.stop(), 0) << daemon.log();
}

}  // namespace interfaces_test
}  // namespace rangefit::test
