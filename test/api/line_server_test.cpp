// The line-based TCP interface against a fake service, on loopback.
#include "api/line_server.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <future>
#include <vector>

#include "api/listen_address.hpp"
#include "fake_backend.hpp"

namespace rangefit::api {
namespace line_server_test {

// A raw TCP client reading answers line by line.
class LineClient {
 public:
  explicit LineClient(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~LineClient() { ::close(fd_); }
  bool connected() const { return connected_; }
  void send(const std::string& text) const { ::send(fd_, text.data(), text.size(), MSG_NOSIGNAL); }
  // The next line, or "" after timeout_ms or when the server closed.
  std::string line(int timeout_ms = 3000) {
    while (buffer_.find('\n') == std::string::npos) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, timeout_ms) != 1) return "";
      char chunk[4096];
      const ssize_t n = ::recv(fd_, chunk, sizeof chunk, 0);
      if (n <= 0) return "";
      buffer_.append(chunk, static_cast<std::size_t>(n));
    }
    const auto end = buffer_.find('\n');
    std::string l = buffer_.substr(0, end);
    buffer_.erase(0, end + 1);
    return l;
  }
  nlohmann::json answer(int timeout_ms = 3000) {
    return nlohmann::json::parse(line(timeout_ms), nullptr, false);
  }
  // True when the server closed the connection within timeout_ms.
  bool closed(int timeout_ms) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) != 1) return false;
    char c;
    return ::recv(fd_, &c, 1, 0) <= 0;
  }

 private:
  int fd_;
  bool connected_ = false;
  std::string buffer_;
};

using test::kToken;
const std::string kLineRequest =
    R"({"kind": "bore", "bore": {"radius_mm": 5}, "token": ")" + kToken + "\"}";

class Line : public ::testing::Test {
 protected:
  void start(LineOptions o = {}) {
    o.listen = {"127.0.0.1", 0};
    o.write_token = kToken;
    server_ = std::make_unique<LineServer>(backend_, o);
    std::string error;
    ASSERT_TRUE(server_->start(&error)) << error;
  }
  test::FakeBackend backend_;
  std::unique_ptr<LineServer> server_;
};

TEST_F(Line, OneAnswerPerRequestLineInOrder) {
  start();
  LineClient c(server_->port());
  ASSERT_TRUE(c.connected());
  c.send(
      kLineRequest + "\n" + R"({"op": "state"})" + "\r\n" +
      R"({"op": "detect", "request": {"kind": "bore", "id": "mine"}, "wait": false, "token": ")" +
      kToken + "\"}\n");
  const nlohmann::json first = c.answer();
  EXPECT_EQ(first["status"], "ok");
  EXPECT_EQ(first["found"], true);
  EXPECT_EQ(c.answer()["state"], "ready");
  const nlohmann::json queued = c.answer();
  EXPECT_EQ(queued["status"], "accepted");
  EXPECT_EQ(queued["id"], "mine");
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  c.send(R"({"op": "result", "id": "mine"})"
         "\n"
         R"({"op": "result", "id": "other"})"
         "\n");
  EXPECT_EQ(c.answer()["status"], "ok");
  EXPECT_EQ(c.answer()["status"], "not_found");
}

TEST_F(Line, BadJsonIsAnsweredAndTheConnectionStays) {
  start();
  LineClient c(server_->port());
  c.send("{ not json\n[1]\n{\"op\": \"dance\"}\n{\"op\": \"result\"}\n" + kLineRequest + "\n");
  for (int i = 0; i < 4; ++i) {
    const nlohmann::json a = c.answer();
    EXPECT_EQ(a["status"], "bad_request") << a;
    EXPECT_TRUE(a.contains("error"));
  }
  EXPECT_EQ(c.answer()["status"], "ok");
  EXPECT_EQ(backend_.detections, 1);
}

TEST_F(Line, DetectionNeedsTheTokenOtherOpsDoNot) {
  start();
  LineClient c(server_->port());
  c.send(std::string(R"({"kind": "bore", "bore": {"radius_mm": 5}})") + "\n" +
         R"({"op": "detect", "request": {"kind": "bore"}, "token": "wrong"})" + "\n" +
         R"({"op": "state"})" + "\n" + R"({"op": "results", "n": 3})" + "\n");
  EXPECT_EQ(c.answer()["status"], "forbidden");
  EXPECT_EQ(c.answer()["status"], "forbidden");
  EXPECT_EQ(c.answer()["status"], "ok");
  const nlohmann::json recent = c.answer();
  EXPECT_EQ(recent["status"], "ok");
  EXPECT_TRUE(recent["results"].empty());
  EXPECT_EQ(backend_.detections, 0);
}

TEST_F(Line, OverlongLinesCloseTheConnection) {
  LineOptions o;
  o.max_line_bytes = 1024;
  start(o);
  LineClient c(server_->port());
  c.send(std::string(5000, 'x'));  // no newline: the server must not buffer without end
  EXPECT_EQ(c.answer()["status"], "too_large");
  EXPECT_TRUE(c.closed(2000));
  LineClient next(server_->port());
  next.send(kLineRequest + "\n");
  EXPECT_EQ(next.answer()["status"], "ok");
}

TEST_F(Line, BusyAndTooManyConnections) {
  LineOptions o;
  o.max_connections = 2;
  start(o);
  backend_.capacity = 0;
  LineClient a(server_->port()), b(server_->port());
  a.send(kLineRequest + "\n");
  EXPECT_EQ(a.answer()["status"], "busy");  // the cell's queue is full
  b.send(R"({"op": "state"})"
         "\n");
  EXPECT_EQ(b.answer()["status"], "ok");
  LineClient third(server_->port());
  EXPECT_EQ(third.answer()["status"], "busy");  // no room for a third connection
  EXPECT_TRUE(third.closed(2000));
}

TEST_F(Line, IdleClientsAreClosed) {
  LineOptions o;
  o.idle_timeout = std::chrono::milliseconds(200);
  start(o);
  LineClient c(server_->port());
  c.send("{\"op\":");  // half a line, then silence
  EXPECT_TRUE(c.closed(3000));
}

TEST_F(Line, FiftyConcurrentClients) {
  backend_.detect_time = std::chrono::milliseconds(20);
  start();
  std::vector<std::future<std::string>> clients;
  for (int i = 0; i < 50; ++i) {
    clients.push_back(std::async(std::launch::async, [this] {
      LineClient c(server_->port());
      c.send(kLineRequest + "\n");
      return c.answer(5000).value("status", std::string("none"));
    }));
  }
  for (auto& f : clients) EXPECT_EQ(f.get(), "ok");
  EXPECT_EQ(backend_.detections, 50);
}

TEST(ListenAddress, Parses) {
  std::string error;
  const auto a = parse_listen_address("127.0.0.1:8080", &error);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->host, "127.0.0.1");
  EXPECT_EQ(a->port, 8080);
  EXPECT_EQ(parse_listen_address("localhost:0", &error)->host, "127.0.0.1");
  for (const char* bad : {"127.0.0.1", "127.0.0.1:", "127.0.0.1:http", "127.0.0.1:70000",
                          "example.com:80", ":80", "127.0.0.1:80x"}) {
    EXPECT_FALSE(parse_listen_address(bad, &error)) << bad;
  }
}

}  // namespace line_server_test
}  // namespace rangefit::api
