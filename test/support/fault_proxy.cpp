#include "test/support/fault_proxy.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <deque>
#include <list>
#include <utility>
#include <vector>

namespace rangefit::sim {
namespace {

struct Pipe {
  int client = -1;
  int upstream = -1;
  std::deque<std::pair<hal::Timestamp, std::vector<std::uint8_t>>> replies;  // due time, bytes
};

void reset_socket(int fd) {
  const linger l{1, 0};  // close with RST instead of FIN
  setsockopt(fd, SOL_SOCKET, SO_LINGER, &l, sizeof l);
  ::close(fd);
}

sockaddr_in loopback(const std::string& host, int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, host.c_str(), &a.sin_addr);
  return a;
}

}  // namespace

FaultProxy::FaultProxy(std::string upstream_host, int upstream_port)
    : upstream_host_(std::move(upstream_host)), upstream_port_(upstream_port) {}

FaultProxy::~FaultProxy() { stop(); }

bool FaultProxy::open_listener() {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int on = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  sockaddr_in a = loopback("127.0.0.1", port_);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 8) != 0) {
    ::close(fd);
    return false;
  }
  socklen_t len = sizeof a;
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  port_ = ntohs(a.sin_port);
  listen_fd_ = fd;
  return true;
}

hal::Status FaultProxy::start(int listen_port) {
  if (running_) return hal::Status::Ok();
  port_ = listen_port;
  if (!open_listener()) {
    return hal::Status::Error("fault proxy: cannot listen on 127.0.0.1:" +
                              std::to_string(listen_port));
  }
  running_ = true;
  thread_ = std::thread([this] { run(); });
  return hal::Status::Ok();
}

void FaultProxy::stop() {
  if (!running_.exchange(false)) return;
  if (thread_.joinable()) thread_.join();
}

void FaultProxy::run() {
  std::list<Pipe> pipes;
  std::array<std::uint8_t, 4096> buf{};
  const auto drop_pipe = [&](std::list<Pipe>::iterator it, bool rst) {
    if (rst) {
      reset_socket(it->client), reset_socket(it->upstream), ++resets_;
      last_reset_ns_ = hal::monotonic_now().count();
    } else {
      ::close(it->client), ::close(it->upstream);
    }
    --connections_;
    return pipes.erase(it);
  };
  while (running_) {
    if (!listening_ && listen_fd_ >= 0) {
      ::close(listen_fd_);
      listen_fd_ = -1;
      for (auto it = pipes.begin(); it != pipes.end();) it = drop_pipe(it, true);
    } else if (listening_ && listen_fd_ < 0 && !open_listener()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    std::vector<pollfd> fds;
    if (listen_fd_ >= 0) fds.push_back({listen_fd_, POLLIN, 0});
    for (const Pipe& p : pipes) {
      fds.push_back({p.client, POLLIN, 0});
      fds.push_back({p.upstream, POLLIN, 0});
    }
    ::poll(fds.data(), fds.size(), 1);
    std::size_t i = 0;
    if (listen_fd_ >= 0 && (fds[i++].revents & POLLIN)) {
      const int c = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
      const int u = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
      sockaddr_in a = loopback(upstream_host_, upstream_port_);
      if (c >= 0 && ::connect(u, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
        const int on = 1;
        setsockopt(c, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
        setsockopt(u, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
        pipes.push_back({c, u, {}});
        ++connections_;
      } else {
        if (c >= 0) reset_socket(c);
        ::close(u);
      }
    }
    const hal::Timestamp now = hal::monotonic_now();
    for (auto it = pipes.begin(); it != pipes.end() && i + 1 < fds.size() + 1;) {
      const short from_client = fds[i].revents, from_upstream = fds[i + 1].revents;
      i += 2;
      bool closed = false, rst = false;
      if (from_client & (POLLIN | POLLHUP | POLLERR)) {
        const ssize_t n = ::recv(it->client, buf.data(), buf.size(), 0);
        if (n <= 0) {
          closed = true;
        } else if (black_hole_) {
        } else if (reset_next_.exchange(false)) {
          closed = rst = true;
        } else if (!drop_next_.exchange(false)) {
          ::send(it->upstream, buf.data(), static_cast<std::size_t>(n), MSG_NOSIGNAL);
        }
      }
      if (!closed && (from_upstream & (POLLIN | POLLHUP | POLLERR))) {
        const ssize_t n = ::recv(it->upstream, buf.data(), buf.size(), 0);
        if (n <= 0) {
          closed = true;
        } else if (!black_hole_) {
          it->replies.emplace_back(now + hal::Duration(reply_delay_ns_.load()),
                                   std::vector<std::uint8_t>(buf.begin(), buf.begin() + n));
        }
      }
      while (!closed && !it->replies.empty() && it->replies.front().first <= now) {
        const auto& bytes = it->replies.front().second;
        ::send(it->client, bytes.data(), bytes.size(), MSG_NOSIGNAL);
        it->replies.pop_front();
      }
      it = closed ? drop_pipe(it, rst) : std::next(it);
    }
  }
  for (auto it = pipes.begin(); it != pipes.end();) it = drop_pipe(it, false);
  if (listen_fd_ >= 0) ::close(listen_fd_);
  listen_fd_ = -1;
}

}  // namespace rangefit::sim
