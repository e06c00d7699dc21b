// The HTTP interface against a fake service, on loopback: the routes a robot program uses, and
// what a hostile or careless client does (bad JSON, huge bodies, silence, 50 at once, a busy cell).
#include "api/http_server.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <vector>

#include "fake_backend.hpp"

namespace rangefit::api {
namespace http_server_test {

const std::string kRequest = R"({"kind": "bore", "bore": {"radius_mm": 5}})";
using test::kToken;

class Http : public ::testing::Test {
 protected:
  void start(HttpOptions o = {}) {
    o.listen = {"127.0.0.1", 0};
    if (o.write_token.empty() && !read_only_) o.write_token = kToken;
    server_ = std::make_unique<HttpServer>(backend_, o);
    std::string error;
    ASSERT_TRUE(server_->start(&error)) << error;
    ASSERT_GT(server_->port(), 0);
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", server_->port());
    c.set_read_timeout(10, 0);
    c.set_bearer_token_auth(kToken);
    return c;
  }
  static nlohmann::json body(const httplib::Result& r) {
    return nlohmann::json::parse(r->body, nullptr, false);
  }

  test::FakeBackend backend_;
  std::unique_ptr<HttpServer> server_;
  bool read_only_ = false;
};

TEST_F(Http, DetectWaitsForTheResult) {
  start();
  auto c = client();
  const auto r = c.Post("/v1/detect", kRequest, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  const nlohmann::json j = body(r);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["found"], true);
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/json");
  // The result stays there by id.
  const auto again = c.Get("/v1/results/" + j["request_id"].get<std::string>());
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 200);
  EXPECT_EQ(body(again)["bore_radius_mm"], 5.0);
}

TEST_F(Http, DetectWithoutWaitingGivesAnIdToPoll) {
  backend_.detect_time = std::chrono::milliseconds(200);
  const auto dir = std::filesystem::temp_directory_path() / "rangefit_http_test_cloud.ply";
  std::ofstream(dir) << "ply\n";
  backend_.cloud_file = dir;
  start();
  auto c = client();
  const auto r = c.Post("/v1/detect?wait=0", kRequest, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202);
  const std::string id = body(r)["id"];
  const auto running = c.Get("/v1/results/" + id);
  ASSERT_TRUE(running);
  EXPECT_EQ(running->status, 202);
  const auto early = c.Get("/v1/results/" + id + "/cloud.ply");
  ASSERT_TRUE(early);
  EXPECT_EQ(early->status, 404) << early->body;  // not finished yet
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  EXPECT_EQ(c.Get("/v1/results/" + id)->status, 200);
  const auto cloud = c.Get("/v1/results/" + id + "/cloud.ply");
  ASSERT_TRUE(cloud);
  EXPECT_EQ(cloud->status, 200);
  EXPECT_EQ(cloud->body, "ply\n");
  EXPECT_EQ(c.Get("/v1/results/" + id + "/picture.png")->status, 404);
  std::filesystem::remove(dir);
}

// What a learn or calibrate request wrote is served as text; names the service does not hand
// out never reach the backend.
TEST_F(Http, ALearntModelIsServedAsTextAndOtherNamesAreNotAsked) {
  const auto file = std::filesystem::temp_directory_path() / "rangefit_http_test_model.toml";
  std::ofstream(file) << "name = \"taught\"\n";
  backend_.model_file = file;
  start();
  auto c = client();
  const auto r = c.Post("/v1/detect", kRequest, "application/json");
  ASSERT_TRUE(r);
  const std::string id = body(r)["request_id"];
  const auto model = c.Get("/v1/results/" + id + "/model.toml");
  ASSERT_TRUE(model);
  EXPECT_EQ(model->status, 200);
  EXPECT_EQ(model->body, "name = \"taught\"\n");
  EXPECT_EQ(model->get_header_value("Content-Type"), "text/plain; charset=utf-8");
  for (const char* name : {"request.json", "result.json", "..", "model.toml.bak"}) {
    const auto other = c.Get("/v1/results/" + id + "/" + name);
    ASSERT_TRUE(other);
    EXPECT_EQ(other->status, 404) << name;
  }
  EXPECT_EQ(backend_.asked_files, std::vector<std::string>{"model.toml"});
  std::filesystem::remove(file);
}

TEST_F(Http, StateUnknownIdsAndRoutes) {
  start();
  auto c = client();
  const auto state = c.Get("/v1/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(state->status, 200);
  EXPECT_EQ(body(state)["state"], "ready");
  EXPECT_EQ(c.Get("/v1/results/nope")->status, 404);
  // No way out of the results: ids are plain names, other files do not exist.
  EXPECT_EQ(c.Get("/v1/results/..%2F..%2Fetc%2Fpasswd")->status, 404);
  EXPECT_EQ(c.Get("/v1/results/x/../../etc/passwd")->status, 404);
  EXPECT_EQ(c.Get("/v1/results/x/request.json")->status, 404);
  const auto missing = c.Get("/index.html");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(body(missing)["status"], "not_found");
}

TEST_F(Http, DetectionNeedsTheConfiguredTokenReadsDoNot) {
  start();
  httplib::Client anonymous("127.0.0.1", server_->port());
  const auto none = anonymous.Post("/v1/detect", kRequest, "application/json");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 403);
  EXPECT_EQ(body(none)["status"], "forbidden");
  anonymous.set_bearer_token_auth(kToken + "x");
  EXPECT_EQ(anonymous.Post("/v1/detect", kRequest, "application/json")->status, 403);
  anonymous.set_bearer_token_auth(kToken.substr(0, 5));
  EXPECT_EQ(anonymous.Post("/v1/detect", kRequest, "application/json")->status, 403);
  EXPECT_EQ(backend_.detections, 0);
  EXPECT_EQ(anonymous.Get("/v1/state")->status, 200);
  httplib::Client header("127.0.0.1", server_->port());
  const auto ok =
      header.Post("/v1/detect", {{"X-Rangefit-Token", kToken}}, kRequest, "application/json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  const auto recent = anonymous.Get("/v1/results?n=5");
  ASSERT_TRUE(recent);
  EXPECT_EQ(body(recent)["results"].size(), 1u);
  EXPECT_EQ(anonymous.Get("/v1/results?n=-1")->status, 400);
}

TEST_F(Http, WithoutAConfiguredTokenEveryDetectionIsForbidden) {
  read_only_ = true;
  start();
  auto c = client();  // sends a token, but none is configured
  const auto r = c.Post("/v1/detect", kRequest, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_NE(body(r)["error"].get<std::string>().find("read-only"), std::string::npos);
  EXPECT_EQ(backend_.detections, 0);
}

TEST_F(Http, ServesTheStaticFilesGivenAndNothingElse) {
  static const std::string page = "<!doctype html><title>cell</title>";
  HttpOptions o;
  o.files.push_back({"/index.html", "text/html", page});
  o.files.push_back({"/app.js", "text/javascript", "console.log(1);"});
  start(o);
  auto c = client();
  for (const char* path : {"/", "/index.html"}) {
    const auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 200) << path;
    EXPECT_EQ(r->body, page);
    EXPECT_EQ(r->get_header_value("Content-Type"), "text/html");
  }
  EXPECT_EQ(c.Get("/app.js")->body, "console.log(1);");
  EXPECT_EQ(c.Get("/../CMakeLists.txt")->status, 404);
  EXPECT_EQ(c.Get("/etc/passwd")->status, 404);
}

TEST_F(Http, BadJsonIsABadRequest) {
  start();
  auto c = client();
  for (const std::string& bad : {std::string("{ not json"), std::string("[1, 2]"), std::string(""),
                                 std::string(R"({"no": "kind"})")}) {
    const auto r = c.Post("/v1/detect", bad, "application/json");
    ASSERT_TRUE(r) << bad;
    EXPECT_EQ(r->status, 400) << bad;
    EXPECT_EQ(body(r)["status"], "bad_request") << bad;
    EXPECT_FALSE(body(r)["error"].get<std::string>().empty());
  }
  EXPECT_EQ(backend_.detections, 0);
}

TEST_F(Http, HugeBodiesAreRefused) {
  HttpOptions o;
  o.max_body_bytes = 4096;
  start(o);
  auto c = client();
  const std::string huge = R"({"kind": "bore", "pad": ")" + std::string(1 << 20, 'x') + "\"}";
  const auto r = c.Post("/v1/detect", huge, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_EQ(backend_.detections, 0);
  // And the server goes on.
  EXPECT_EQ(client().Post("/v1/detect", kRequest, "application/json")->status, 200);
}

TEST_F(Http, BusyCellAnswers503) {
  backend_.capacity = 1;
  backend_.detect_time = std::chrono::milliseconds(300);
  start();
  auto first = std::async(std::launch::async, [this] {
    return client().Post("/v1/detect", kRequest, "application/json")->status;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto busy = client().Post("/v1/detect", kRequest, "application/json");
  ASSERT_TRUE(busy);
  EXPECT_EQ(busy->status, 503);
  EXPECT_EQ(body(busy)["status"], "busy");
  EXPECT_EQ(busy->get_header_value("Retry-After"), "1");
  EXPECT_EQ(first.get(), 200);
}

TEST_F(Http, FiftyConcurrentClientsAllGetAnswers) {
  backend_.detect_time = std::chrono::milliseconds(20);
  HttpOptions o;
  o.max_waiting = 50;  // every one may wait: all 50 connections are served at once
  start(o);
  std::vector<std::future<int>> clients;
  for (int i = 0; i < 50; ++i) {
    clients.push_back(std::async(std::launch::async, [this] {
      const auto r = client().Post("/v1/detect", kRequest, "application/json");
      return r ? r->status : -100 - static_cast<int>(r.error());
    }));
  }
  for (auto& f : clients) EXPECT_EQ(f.get(), 200);
  EXPECT_EQ(backend_.detections, 50);
}

// Connects and sends half a request, then nothing.
int silent_client(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) return -1;
  const std::string part = "POST /v1/detect HTTP/1.1\r\nHost: x\r\nContent-Length: 100\r\n\r\n{";
  ::send(fd, part.data(), part.size(), MSG_NOSIGNAL);
  return fd;
}

TEST_F(Http, SlowClientsAreDroppedAndDoNotBlockOthers) {
  HttpOptions o;
  o.max_waiting = 1;
  o.threads = 1 + kFreeThreads;
  o.read_timeout = std::chrono::milliseconds(300);
  start(o);
  std::vector<int> slow;
  for (int i = 0; i < o.threads; ++i) slow.push_back(silent_client(server_->port()));  // all
  EXPECT_EQ(client().Post("/v1/detect", kRequest, "application/json")->status, 200);
  for (const int fd : slow) {
    ASSERT_GE(fd, 0);
    pollfd p{fd, POLLIN, 0};
    ASSERT_EQ(::poll(&p, 1, 3000), 1) << "the server did not drop a silent client";
    char buf[512];
    // Closed, possibly after an error answer: reading reaches the end.
    while (::recv(fd, buf, sizeof buf, 0) > 0) {
    }
    ::close(fd);
  }
  EXPECT_EQ(backend_.detections, 1);
}

// A waiting client holds a server thread until its result is there. More waiting clients than
// the server has threads, while the cell is busy: the ones over the bound hear busy at once, the
// state still answers, and the ones waiting get their results when the scans end.
TEST_F(Http, WaitingClientsBeyondTheBoundHearBusyAndTheStateStillAnswers) {
  HttpOptions o;
  o.max_waiting = 3;
  o.threads = 4;  // raised to 3 + kFreeThreads
  start(o);
  backend_.hold = true;  // every scan runs until released
  const int clients = 12;
  ASSERT_GT(clients, o.max_waiting + kFreeThreads);
  std::vector<std::future<httplib::Result>> waiters;
  for (int i = 0; i < clients; ++i) {
    waiters.push_back(std::async(std::launch::async, [this, i] {
      const nlohmann::json request = {{"kind", "bore"},
                                      {"id", std::string("w").append(std::to_string(i))}};
      return client().Post("/v1/detect", request.dump(), "application/json");
    }));
  }
  // On a failed assertion too: the scans end before the waiters' futures are joined.
  const std::unique_ptr<std::atomic<bool>, void (*)(std::atomic<bool>*)> release(
      &backend_.hold, [](std::atomic<bool>* hold) { *hold = false; });
  // Those over the bound are answered while the others still wait.
  int busy = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (busy < clients - o.max_waiting && std::chrono::steady_clock::now() < deadline) {
    for (auto& w : waiters) {
      if (!w.valid() || w.wait_for(std::chrono::seconds(0)) != std::future_status::ready) continue;
      const httplib::Result r = w.get();
      ASSERT_TRUE(r) << "a client over the bound got no answer";
      EXPECT_EQ(r->status, 503) << r->body;
      EXPECT_EQ(r->get_header_value("Retry-After"), "1");
      EXPECT_EQ(body(r)["status"], "busy");
      EXPECT_NE(body(r)["error"].get<std::string>().find("wait=0"), std::string::npos) << r->body;
      ++busy;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(busy, clients - o.max_waiting);
  // Every thread but the waiters' is free: the state and the results list answer now.
  auto reader = client();
  reader.set_read_timeout(5, 0);
  const auto state = reader.Get("/v1/state");
  ASSERT_TRUE(state) << "GET /v1/state got no answer while clients waited";
  EXPECT_EQ(state->status, 200);
  EXPECT_EQ(body(state)["in_flight"], o.max_waiting);
  const auto recent = reader.Get("/v1/results?n=5");
  ASSERT_TRUE(recent);
  EXPECT_EQ(recent->status, 200);
  // A client that does not wait is still taken.
  EXPECT_EQ(client().Post("/v1/detect?wait=0", kRequest, "application/json")->status, 202);

  backend_.hold = false;
  int found = 0;
  for (auto& w : waiters) {
    if (!w.valid()) continue;
    const httplib::Result r = w.get();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << r->body;
    found += body(r)["found"] == true;
  }
  EXPECT_EQ(found, o.max_waiting);
}

TEST_F(Http, PortInUseIsAnError) {
  start();
  HttpOptions o;
  o.listen = {"127.0.0.1", server_->port()};
  HttpServer second(backend_, o);
  std::string error;
  EXPECT_FALSE(second.start(&error));
  EXPECT_NE(error.find(std::to_string(server_->port())), std::string::npos) << error;
}

}  // namespace http_server_test
}  // namespace rangefit::api
