#include "drivers/can/socketcan_transport.hpp"

#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/errqueue.h>
#include <linux/net_tstamp.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "drivers/can/linux_frame.hpp"

namespace rangefit::drivers::can {

namespace {
hal::Status errno_status(const std::string& what) {
  return hal::Status::Error(what + ": " + std::strerror(errno));
}

bool link_error(int err) { return err == ENETDOWN || err == ENXIO || err == ENODEV; }

std::int64_t ns_of(const timespec& ts) {
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::int64_t clock_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return ns_of(ts);
}
}  // namespace

SocketCanTransport::SocketCanTransport(SocketCanConfig config) : config_(std::move(config)) {
  for (std::size_t i = 0; i < kBatch; ++i) {
    iov_[i] = {&raw_[i], sizeof(canfd_frame)};
    msgs_[i].msg_hdr.msg_iov = &iov_[i];
    msgs_[i].msg_hdr.msg_iovlen = 1;
  }
}

SocketCanTransport::~SocketCanTransport() { close_socket(); }

void SocketCanTransport::close_socket() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

hal::Status SocketCanTransport::open() {
  close_socket();
  const int fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) return errno_status("socket(AF_CAN)");
  fd_ = fd;
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, config_.interface.c_str(), IFNAMSIZ - 1);
  if (ioctl(fd, SIOCGIFINDEX, &ifr) < 0) return errno_status(config_.interface);
  const int ifindex = ifr.ifr_ifindex;
  if (ioctl(fd, SIOCGIFFLAGS, &ifr) < 0) return errno_status(config_.interface);
  if (!(ifr.ifr_flags & IFF_UP)) return hal::Status::Error(config_.interface + ": interface down");

  const int one = 1;
  if (config_.fd && setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &one, sizeof(one)) < 0) {
    return errno_status("CAN_RAW_FD_FRAMES");
  }
  std::vector<can_filter> filters;
  for (std::uint32_t id : config_.filter.ids) {
    filters.push_back({id, CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG});
  }
  if (!filters.empty() &&
      setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                 static_cast<socklen_t>(filters.size() * sizeof(can_filter))) < 0) {
    return errno_status("CAN_RAW_FILTER");
  }
  // Bus-off, controller state changes and restarts; not CAN_ERR_PROT/BUSERROR, which arrive for
  // every erroneous bit on a disturbed bus and would flood the receive path.
  const can_err_mask_t err_mask =
      config_.filter.error_frames
          ? (CAN_ERR_BUSOFF | CAN_ERR_CRTL | CAN_ERR_RESTARTED | CAN_ERR_TX_TIMEOUT)
          : 0;
  if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof(err_mask)) < 0) {
    return errno_status("CAN_RAW_ERR_FILTER");
  }
  const int own = config_.filter.own_frames ? 1 : 0;
  if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof(own)) < 0) {
    return errno_status("CAN_RAW_RECV_OWN_MSGS");
  }
  if (setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof(one)) < 0) {
    return errno_status("SO_RXQ_OVFL");
  }
  const int ts_flags = SOF_TIMESTAMPING_RX_SOFTWARE | SOF_TIMESTAMPING_SOFTWARE |
                       SOF_TIMESTAMPING_RX_HARDWARE | SOF_TIMESTAMPING_RAW_HARDWARE;
  if (setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPING, &ts_flags, sizeof(ts_flags)) < 0) {
    return errno_status("SO_TIMESTAMPING");
  }
  if (config_.receive_buffer > 0) {
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &config_.receive_buffer, sizeof(int));
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifindex;
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) < 0) return errno_status("bind");
  last_overflow_ = 0;
  have_offset_ = false;
  return hal::Status::Ok();
}

hal::Status SocketCanTransport::reopen() {
  AtomicTransportCounters::bump(counters_.reopens);
  hal::Status s = open();
  if (!s) close_socket();
  return s;
}

TxResult SocketCanTransport::send(const CanFrame& frame) {
  if (fd_ < 0) return TxResult::kLinkDown;
  canfd_frame raw;
  const std::size_t n = to_linux(frame, raw);
  if (::write(fd_, &raw, n) == static_cast<ssize_t>(n)) {
    AtomicTransportCounters::bump(counters_.tx_frames);
    return TxResult::kOk;
  }
  if (errno == ENOBUFS || errno == EAGAIN) {
    AtomicTransportCounters::bump(counters_.tx_buffer_full);
    return TxResult::kBufferFull;
  }
  return link_error(errno) ? TxResult::kLinkDown : TxResult::kError;
}

void SocketCanTransport::sample_clock_offset() {
  // Bracket a CLOCK_REALTIME read with two monotonic reads; the midpoint pairs them.
  const std::int64_t m0 = clock_ns(CLOCK_MONOTONIC);
  const std::int64_t r = clock_ns(CLOCK_REALTIME);
  const std::int64_t m1 = clock_ns(CLOCK_MONOTONIC);
  const std::int64_t offset = r - (m0 + (m1 - m0) / 2);
  const std::int64_t jump = offset - realtime_offset_ns_;
  if (have_offset_ &&
      (jump > config_.step_threshold.count() || -jump > config_.step_threshold.count())) {
    AtomicTransportCounters::bump(counters_.clock_steps);
  }
  realtime_offset_ns_ = offset;
  have_offset_ = true;
}

hal::Timestamp SocketCanTransport::convert_stamp(const msghdr& msg, hal::Timestamp read_mono) {
  std::int64_t realtime = 0;
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr;
       c = CMSG_NXTHDR(const_cast<msghdr*>(&msg), c)) {
    if (c->cmsg_level != SOL_SOCKET) continue;
    if (c->cmsg_type == SO_RXQ_OVFL) {
      std::uint32_t dropped = 0;
      std::memcpy(&dropped, CMSG_DATA(c), sizeof(dropped));
      if (dropped != last_overflow_) {
        AtomicTransportCounters::bump(counters_.rx_overflow, dropped - last_overflow_);
        last_overflow_ = dropped;
      }
    } else if (c->cmsg_type == SO_TIMESTAMPING) {
      scm_timestamping ts{};
      std::memcpy(&ts, CMSG_DATA(c), sizeof(ts));
      realtime = ns_of(ts.ts[0]);
      if (config_.hardware_stamps && ns_of(ts.ts[2]) != 0) realtime = ns_of(ts.ts[2]);
    }
  }
  hal::Timestamp stamp{realtime - realtime_offset_ns_};
  // A stamp must be no later than our read and not older than the socket could hold; zero,
  // future or backward stamps (and those straddling a clock step) fall back to the read time.
  if (realtime == 0 || stamp > read_mono || stamp < read_mono - std::chrono::seconds(1) ||
      stamp < last_stamp_) {
    AtomicTransportCounters::bump(counters_.bad_stamps);
    stamp = read_mono;
  }
  last_stamp_ = stamp;
  return stamp;
}

RxResult SocketCanTransport::receive(std::span<CanFrame> out, hal::Duration timeout) {
  RxResult r;
  if (fd_ < 0) {
    r.link_down = true;
    return r;
  }
  // ppoll, not poll: a timeout rounded up to whole milliseconds made every SYNC of a 4 ms
  // cycle up to 1 ms late (the loop waits here until its next tick).
  pollfd pfd{fd_, POLLIN, 0};
  const std::int64_t ns = std::max<std::int64_t>(timeout.count(), 0);
  const timespec ts{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
  if (ppoll(&pfd, 1, &ts, nullptr) <= 0) return r;
  const auto want = static_cast<unsigned>(std::min(out.size(), kBatch));
  for (unsigned i = 0; i < want; ++i) {
    msgs_[i].msg_hdr.msg_control = control_[i].data();
    msgs_[i].msg_hdr.msg_controllen = control_[i].size();
    msgs_[i].msg_hdr.msg_flags = 0;
  }
  const int n = recvmmsg(fd_, msgs_.data(), want, MSG_DONTWAIT, nullptr);
  if (n < 0) {
    r.link_down = link_error(errno);
    return r;
  }
  sample_clock_offset();
  const hal::Timestamp read_mono = hal::monotonic_now();
  for (int i = 0; i < n; ++i) {
    const msghdr& h = msgs_[i].msg_hdr;
    CanFrame& f = out[r.frames];
    if (!from_linux(raw_[i], msgs_[i].msg_len, f)) continue;
    if (h.msg_flags & MSG_CONFIRM) f.flags |= kFrameEcho;
    f.stamp = convert_stamp(h, read_mono);
    if (f.flags & kFrameError) AtomicTransportCounters::bump(counters_.error_frames);
    ++r.frames;
  }
  AtomicTransportCounters::bump(counters_.rx_frames, r.frames);
  return r;
}

}  // namespace rangefit::drivers::can
