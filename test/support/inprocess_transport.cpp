#include "test/support/inprocess_transport.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>

#include "drivers/can/linux_frame.hpp"

namespace rangefit::drivers::can {

namespace {
int to_ms(hal::Duration d) {
  if (d.count() <= 0) return 0;
  return static_cast<int>((d.count() + 999'999) / 1'000'000);
}
}  // namespace

InProcessTransport::InProcessTransport(std::string name, int peer_fd, FrameFilter filter)
    : name_(std::move(name)), peer_fd_(peer_fd), filter_(std::move(filter)) {
  if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK | SOCK_CLOEXEC, 0, echo_fds_) != 0) {
    throw std::runtime_error("in-process CAN: socketpair failed");
  }
}

InProcessTransport::~InProcessTransport() {
  for (int fd : {peer_fd_, echo_fds_[0], echo_fds_[1]}) {
    if (fd >= 0) close(fd);
  }
}

std::pair<std::unique_ptr<InProcessTransport>, std::unique_ptr<InProcessTransport>>
InProcessTransport::make_pair(FrameFilter a, FrameFilter b) {
  int fds[2];
  if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK | SOCK_CLOEXEC, 0, fds) != 0) {
    throw std::runtime_error("in-process CAN: socketpair failed");
  }
  return {std::unique_ptr<InProcessTransport>(new InProcessTransport("inproc-a", fds[0], a)),
          std::unique_ptr<InProcessTransport>(new InProcessTransport("inproc-b", fds[1], b))};
}

TxResult InProcessTransport::send(const CanFrame& frame) {
  if (down_.load()) return TxResult::kLinkDown;
  canfd_frame raw;
  const std::size_t n = to_linux(frame, raw);
  if (::send(peer_fd_, &raw, n, MSG_NOSIGNAL) != static_cast<ssize_t>(n)) {
    if (errno == EAGAIN || errno == ENOBUFS) {
      AtomicTransportCounters::bump(counters_.tx_buffer_full);
      return TxResult::kBufferFull;
    }
    return TxResult::kError;
  }
  AtomicTransportCounters::bump(counters_.tx_frames);
  // Like CAN_RAW_RECV_OWN_MSGS: the echo is queued once the frame is "on the bus".
  if (filter_.own_frames) (void)::send(echo_fds_[1], &raw, n, MSG_NOSIGNAL);
  return TxResult::kOk;
}

bool InProcessTransport::read_one(int fd, CanFrame& out, bool echo) {
  canfd_frame raw;
  const ssize_t n = ::recv(fd, &raw, sizeof(raw), MSG_DONTWAIT);
  if (n <= 0) return false;
  if (!from_linux(raw, static_cast<std::size_t>(n), out)) return false;
  if (echo) out.flags |= kFrameEcho;
  out.stamp = hal::monotonic_now();
  return true;
}

RxResult InProcessTransport::receive(std::span<CanFrame> out, hal::Duration timeout) {
  RxResult r;
  if (down_.load()) {
    r.link_down = true;
    return r;
  }
  pollfd pfd[2] = {{echo_fds_[0], POLLIN, 0}, {peer_fd_, POLLIN, 0}};
  if (poll(pfd, 2, to_ms(timeout)) <= 0) return r;
  // Echoes first: on a real bus our SYNC is on the wire before the replies it triggers.
  for (int i = 0; i < 2; ++i) {
    while (r.frames < out.size()) {
      CanFrame& f = out[r.frames];
      if (!read_one(pfd[i].fd, f, i == 0)) break;
      if ((f.flags & kFrameError) ? !filter_.error_frames : !filter_.accepts(f.id)) continue;
      ++r.frames;
    }
  }
  AtomicTransportCounters::bump(counters_.rx_frames, r.frames);
  return r;
}

hal::Status InProcessTransport::reopen() {
  if (down_.load()) return hal::Status::Error(name_ + ": link down");
  AtomicTransportCounters::bump(counters_.reopens);
  return hal::Status::Ok();
}

}  // namespace rangefit::drivers::can
