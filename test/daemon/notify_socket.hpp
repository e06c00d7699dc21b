#pragma once
// The systemd side of sd_notify(3) for tests: a unix datagram socket whose path is what a
// service finds in $NOTIFY_SOCKET. Messages are read exactly as systemd would receive them.
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <poll.h>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>

namespace rangefit::test {

class NotifySocket {
 public:
  explicit NotifySocket(std::filesystem::path path) : path_(std::move(path)) {
    std::filesystem::remove(path_);
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path_.c_str(), sizeof(addr.sun_path) - 1);
    bound_ = bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  }
  ~NotifySocket() {
    close(fd_);
    std::filesystem::remove(path_);
  }
  bool ok() const { return bound_; }
  const std::filesystem::path& path() const { return path_; }

  // Next datagram, or "" after timeout (generous: a missing message fails the test, a slow one
  // does not).
  std::string next(std::chrono::milliseconds timeout) {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return "";
    char buf[4096];
    const ssize_t n = recv(fd_, buf, sizeof buf, 0);
    return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  }
  // Reads until a datagram containing needle arrives; returns it, or "" on timeout.
  std::string wait_for(const std::string& needle, std::chrono::milliseconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      std::string m = next(std::chrono::milliseconds(200));
      if (m.find(needle) != std::string::npos) return m;
    }
    return "";
  }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  bool bound_ = false;
};

}  // namespace rangefit::test
