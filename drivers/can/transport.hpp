#pragma once
// The CAN transport seam: a driver sends and receives CanFrames through this interface and never
// sees a socket. Two implementations: SocketCAN raw sockets (socketcan_transport.hpp) and an
// in-process socket pair for unit tests (test/support/inprocess_transport.hpp).
//
// Contract: send() never blocks (a full tx queue is normal on a loaded bus and only counted);
// receive() waits up to a timeout, fills a caller-provided span and neither allocates nor locks.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "drivers/can/can_frame.hpp"
#include "hal/device.hpp"
#include "hal/time.hpp"

namespace rangefit::drivers::can {

enum class TxResult : std::uint8_t {
  kOk,
  kBufferFull,  // ENOBUFS/EAGAIN: tx queue full, frame not sent (counted)
  kLinkDown,    // ENETDOWN/ENXIO: interface down; the driver reopens with back-off
  kError,       // anything else (bad frame, closed transport)
};

struct RxResult {
  std::size_t frames = 0;  // frames written to the output span
  bool link_down = false;  // interface went down; reopen() before receiving again
};

// Plain snapshot of a transport's counters (they only ever increase).
struct TransportCounters {
  std::uint64_t rx_frames = 0;
  std::uint64_t tx_frames = 0;
  std::uint64_t rx_overflow = 0;  // frames the kernel dropped before we read them (SO_RXQ_OVFL)
  std::uint64_t tx_buffer_full = 0;
  std::uint64_t error_frames = 0;  // bus errors reported as error frames
  std::uint64_t bad_stamps = 0;    // zero or backward stamps replaced by the read time
  std::uint64_t clock_steps = 0;   // wall-clock steps seen while converting stamps
  std::uint64_t reopens = 0;
};

// Atomic counters bumped by the receive path; snapshot() is safe from any thread.
struct AtomicTransportCounters {
  std::atomic<std::uint64_t> rx_frames{0}, tx_frames{0}, rx_overflow{0}, tx_buffer_full{0},
      error_frames{0}, bad_stamps{0}, clock_steps{0}, reopens{0};
  static void bump(std::atomic<std::uint64_t>& c, std::uint64_t n = 1) {
    c.fetch_add(n, std::memory_order_relaxed);
  }
  TransportCounters snapshot() const;
};

// Which frames a transport delivers. Exact ids only (CAN_SFF_MASK); empty = everything.
struct FrameFilter {
  std::vector<std::uint32_t> ids;
  bool error_frames = true;  // bus-off, controller problems, restarts (never per-bit bus errors)
  bool own_frames = false;   // loop our own frames back with kFrameEcho (SYNC stamps)
  bool accepts(std::uint32_t id) const;
};

class CanTransport {
 public:
  virtual ~CanTransport() = default;
  virtual std::string name() const = 0;
  virtual TxResult send(const CanFrame& frame) = 0;
  virtual RxResult receive(std::span<CanFrame> out, hal::Duration timeout) = 0;
  // Closes and opens the underlying link again (after kLinkDown).
  virtual hal::Status reopen() = 0;
  virtual TransportCounters counters() const = 0;
};

}  // namespace rangefit::drivers::can
