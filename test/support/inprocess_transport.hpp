#pragma once
// A CAN "bus" between two endpoints inside one process: a SOCK_SEQPACKET socket pair carrying
// the kernel's raw canfd_frame bytes, one datagram per frame, so unit tests run the same driver
// and simulator code as the SocketCAN path without AF_CAN. Own-frame echo (for SYNC stamps) goes
// through a second pair. set_link_down() lets tests take the "interface" down and up again.

#include <atomic>
#include <memory>
#include <utility>

#include "drivers/can/transport.hpp"

namespace rangefit::drivers::can {

class InProcessTransport final : public CanTransport {
 public:
  ~InProcessTransport() override;
  InProcessTransport(const InProcessTransport&) = delete;
  InProcessTransport& operator=(const InProcessTransport&) = delete;

  std::string name() const override { return name_; }
  TxResult send(const CanFrame& frame) override;
  RxResult receive(std::span<CanFrame> out, hal::Duration timeout) override;
  hal::Status reopen() override;
  TransportCounters counters() const override { return counters_.snapshot(); }

  void set_filter(FrameFilter filter) { filter_ = std::move(filter); }
  // Fault injection: while down, send() reports kLinkDown, receive() link_down, reopen() fails.
  void set_link_down(bool down) { down_.store(down); }

  // Two connected endpoints; `a` usually the driver, `b` the simulated devices.
  static std::pair<std::unique_ptr<InProcessTransport>, std::unique_ptr<InProcessTransport>>
  make_pair(FrameFilter a = {}, FrameFilter b = {});

 private:
  InProcessTransport(std::string name, int peer_fd, FrameFilter filter);
  bool read_one(int fd, CanFrame& out, bool echo);

  std::string name_;
  int peer_fd_ = -1;
  int echo_fds_[2] = {-1, -1};  // [0] read, [1] write
  FrameFilter filter_;
  std::atomic<bool> down_{false};
  AtomicTransportCounters counters_;
};

}  // namespace rangefit::drivers::can
