#pragma once
// SocketCAN raw transport (CAN and CAN FD). Exact-id kernel filters, an error-frame mask that
// reports bus-off, controller state and restarts but not every bus-bit error, SO_RXQ_OVFL drop
// counting, SO_TIMESTAMPING stamps converted to CLOCK_MONOTONIC with clock-step detection,
// recvmmsg batches and non-blocking writes. Receive neither allocates nor locks nor logs.

#include <linux/can.h>
#include <sys/socket.h>

#include <array>
#include <string>

#include "drivers/can/transport.hpp"

namespace rangefit::drivers::can {

struct SocketCanConfig {
  std::string interface = "can0";
  FrameFilter filter;
  bool fd = false;         // accept and send CAN FD frames (CAN_RAW_FD_FRAMES)
  int receive_buffer = 0;  // SO_RCVBUF bytes; 0 keeps the kernel default
  // Use the controller's raw hardware stamp when present. Only meaningful when the PHC is
  // disciplined to CLOCK_REALTIME (phc2sys); otherwise the software stamp is used.
  bool hardware_stamps = false;
  hal::Duration step_threshold = std::chrono::milliseconds(1);  // realtime-monotonic jump
};

class SocketCanTransport final : public CanTransport {
 public:
  static constexpr std::size_t kBatch = 64;

  explicit SocketCanTransport(SocketCanConfig config);
  ~SocketCanTransport() override;
  SocketCanTransport(const SocketCanTransport&) = delete;
  SocketCanTransport& operator=(const SocketCanTransport&) = delete;

  // Opens the socket; the constructor does not, so a driver can start with the link absent.
  hal::Status open();
  std::string name() const override { return config_.interface; }
  TxResult send(const CanFrame& frame) override;
  RxResult receive(std::span<CanFrame> out, hal::Duration timeout) override;
  hal::Status reopen() override;
  TransportCounters counters() const override { return counters_.snapshot(); }

 private:
  void close_socket();
  hal::Timestamp convert_stamp(const msghdr& msg, hal::Timestamp read_mono);
  void sample_clock_offset();

  SocketCanConfig config_;
  int fd_ = -1;
  std::uint32_t last_overflow_ = 0;
  std::int64_t realtime_offset_ns_ = 0;  // CLOCK_REALTIME - CLOCK_MONOTONIC
  bool have_offset_ = false;
  hal::Timestamp last_stamp_{};
  AtomicTransportCounters counters_;
  // recvmmsg buffers, preallocated so the receive path does not allocate.
  std::array<canfd_frame, kBatch> raw_{};
  std::array<iovec, kBatch> iov_{};
  std::array<mmsghdr, kBatch> msgs_{};
  std::array<std::array<char, 256>, kBatch> control_{};
};

}  // namespace rangefit::drivers::can
