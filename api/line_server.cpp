#include "api/line_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <list>
#include <memory>
#include <thread>

#include "api/http_server.hpp"

namespace rangefit::api {
namespace {

constexpr int kPollMs = 50;  // how soon a blocked thread notices stop()

bool send_all(int fd, const std::string& text) {
  std::size_t sent = 0;
  while (sent < text.size()) {
    const ssize_t n = ::send(fd, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

bool send_answer(int fd, const Answer& a) { return send_all(fd, answer_json(a).dump() + "\n"); }

}  // namespace

Answer answer_line(Backend& backend, const std::string& line, const std::string& write_token) {
  nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    return error_answer(Status::kBadRequest, "each line must be one JSON object");
  }
  try {
    std::string token;
    if (j.contains("token")) {
      if (j["token"].is_string()) token = j["token"].get<std::string>();
      j.erase("token");
    }
    const bool detect = !j.contains("op") || j["op"] == "detect";
    if (detect && !token_matches(write_token, token)) {
      return error_answer(Status::kForbidden,
                          write_token.empty()
                              ? "read-only: no token is configured for detection requests"
                              : "a detection needs \"token\": the configured token");
    }
    if (!j.contains("op")) return backend.detect(j, true);
    const nlohmann::json& op = j.at("op");
    if (op == "results") {
      const nlohmann::json n = j.contains("n") ? j["n"] : nlohmann::json(10u);
      if (!n.is_number_unsigned() || n.get<std::size_t>() > 1000) {
        return error_answer(Status::kBadRequest, "\"n\" must be a number 0..1000");
      }
      return backend.recent(n.get<std::size_t>());
    }
    if (op == "detect") {
      if (!j.contains("request") || !j["request"].is_object()) {
        return error_answer(Status::kBadRequest, "\"detect\" needs a \"request\" object");
      }
      const nlohmann::json& wait = j.contains("wait") ? j["wait"] : nlohmann::json(true);
      return backend.detect(j["request"], !wait.is_boolean() || wait.get<bool>());
    }
    if (op == "result") {
      if (!j.contains("id") || !j["id"].is_string()) {
        return error_answer(Status::kBadRequest, "\"result\" needs an \"id\" string");
      }
      return backend.result(j["id"].get<std::string>());
    }
    if (op == "state") return backend.state();
    return error_answer(Status::kBadRequest,
                        "op must be \"detect\", \"result\", \"results\" or \"state\"");
  } catch (const std::exception& e) {
    return error_answer(Status::kError, std::string("internal error: ") + e.what());
  }
}

struct LineServer::Impl {
  Backend& backend;
  LineOptions options;
  int listen_fd = -1;
  int port = -1;
  std::atomic<bool> stopping{false};
  std::atomic<int> connections{0};
  std::thread acceptor;
  struct Client {
    std::thread thread;
    std::shared_ptr<std::atomic<bool>> done;
  };
  std::list<Client> clients;  // finished ones are joined as new ones come, the rest at stop()

  Impl(Backend& b, LineOptions o) : backend(b), options(std::move(o)) {}
  void accept_loop();
  void serve(int fd);
  void reap();
};

void LineServer::Impl::reap() {
  for (auto it = clients.begin(); it != clients.end();) {
    if (*it->done) {
      it->thread.join();
      it = clients.erase(it);
    } else {
      ++it;
    }
  }
}

void LineServer::Impl::serve(int fd) {
  std::string buffer;
  auto idle_since = std::chrono::steady_clock::now();
  char chunk[4096];
  while (!stopping) {
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, kPollMs);
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) {
      if (std::chrono::steady_clock::now() - idle_since > options.idle_timeout) break;
      continue;
    }
    const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    idle_since = std::chrono::steady_clock::now();
    buffer.append(chunk, static_cast<std::size_t>(n));
    bool open = true;
    for (std::size_t end; open && (end = buffer.find('\n')) != std::string::npos;) {
      std::string line = buffer.substr(0, end);
      buffer.erase(0, end + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") == std::string::npos) continue;
      if (line.size() > options.max_line_bytes) {
        send_answer(fd,
                    error_answer(Status::kTooLarge,
                                 "line over " + std::to_string(options.max_line_bytes) + " bytes"));
        open = false;
        break;
      }
      open = send_answer(fd, answer_line(backend, line, options.write_token));
    }
    if (!open) break;
    if (buffer.size() > options.max_line_bytes) {
      send_answer(fd,
                  error_answer(Status::kTooLarge,
                               "line over " + std::to_string(options.max_line_bytes) + " bytes"));
      break;
    }
  }
  ::close(fd);
  --connections;
}

void LineServer::Impl::accept_loop() {
  while (!stopping) {
    pollfd p{listen_fd, POLLIN, 0};
    if (::poll(&p, 1, kPollMs) <= 0) continue;
    const int fd = ::accept(listen_fd, nullptr, nullptr);
    if (fd < 0) continue;
    if (connections >= options.max_connections) {
      send_answer(fd, error_answer(Status::kBusy, "too many connections"));
      ::close(fd);
      continue;
    }
    ++connections;
    reap();
    auto done = std::make_shared<std::atomic<bool>>(false);
    clients.push_back({std::thread([this, fd, done] {
                         serve(fd);
                         *done = true;
                       }),
                       done});
  }
}

LineServer::LineServer(Backend& backend, LineOptions options)
    : impl_(std::make_unique<Impl>(backend, std::move(options))) {}

LineServer::~LineServer() { stop(); }

bool LineServer::start(std::string* error) {
  Impl& m = *impl_;
  const std::string where = m.options.listen.host + ":" + std::to_string(m.options.listen.port);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(m.options.listen.port));
  if (inet_pton(AF_INET, m.options.listen.host.c_str(), &addr.sin_addr) != 1) {
    *error = "line server: bad address " + where;
    return false;
  }
  m.listen_fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  ::setsockopt(m.listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (m.listen_fd < 0 ||
      ::bind(m.listen_fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::listen(m.listen_fd, 64) != 0) {
    *error = "line server: cannot listen on " + where + ": " + std::strerror(errno);
    if (m.listen_fd >= 0) ::close(m.listen_fd);
    m.listen_fd = -1;
    return false;
  }
  socklen_t len = sizeof addr;
  ::getsockname(m.listen_fd, reinterpret_cast<sockaddr*>(&addr), &len);
  m.port = ntohs(addr.sin_port);
  m.acceptor = std::thread([&m] { m.accept_loop(); });
  return true;
}

void LineServer::stop() {
  if (!impl_ || !impl_->acceptor.joinable()) return;
  Impl& m = *impl_;
  m.stopping = true;
  m.acceptor.join();
  for (Impl::Client& c : m.clients) c.thread.join();
  m.clients.clear();
  ::close(m.listen_fd);
  m.listen_fd = -1;
}

int LineServer::port() const { return impl_->port; }

}  // namespace rangefit::api
