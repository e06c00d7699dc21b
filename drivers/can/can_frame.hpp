#pragma once
// One CAN or CAN FD frame as the drivers see it, independent of the transport. The transports
// convert to and from the kernel's struct canfd_frame; codecs only ever see this type.

#include <array>
#include <cstdint>
#include <span>

#include "hal/time.hpp"

namespace rangefit::drivers::can {

enum CanFrameFlags : std::uint8_t {
  kFrameFd = 1u << 0,        // CAN FD frame (up to 64 data bytes)
  kFrameBrs = 1u << 1,       // CAN FD bit-rate switch
  kFrameExtended = 1u << 2,  // 29-bit identifier
  kFrameError = 1u << 3,     // error frame: id carries CAN_ERR_* class bits, data the details
  kFrameEcho = 1u << 4,      // our own transmitted frame, looped back (MSG_CONFIRM)
  kFrameRtr = 1u << 5,       // remote request
};

struct CanFrame {
  static constexpr std::size_t kMaxData = 64;
  std::uint32_t id = 0;    // 11- or 29-bit identifier, without flag bits
  std::uint8_t len = 0;    // data length in bytes (0..8 classic, valid FD lengths up to 64)
  std::uint8_t flags = 0;  // CanFrameFlags
  std::array<std::uint8_t, kMaxData> data{};
  hal::Timestamp stamp{};  // receive stamp, host CLOCK_MONOTONIC (0 on frames to send)

  std::span<const std::uint8_t> payload() const { return {data.data(), len}; }
  bool is_fd() const { return (flags & kFrameFd) != 0; }
};

// Smallest valid CAN FD length >= n (0..8, 12, 16, 20, 24, 32, 48, 64); 64 when n > 64.
std::uint8_t fd_padded_length(std::size_t n);
bool valid_fd_length(std::size_t n);

// Builders for the common cases; data beyond the frame's capacity is cut off.
CanFrame make_frame(std::uint32_t id, std::span<const std::uint8_t> bytes);
CanFrame make_fd_frame(std::uint32_t id, std::span<const std::uint8_t> bytes);

// Little-endian field access shared by the codecs (CANopen and the project's profiles are LE).
inline std::uint16_t get_u16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}
inline std::uint32_t get_u32(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | (static_cast<std::uint32_t>(b[at + 1]) << 8) |
         (static_cast<std::uint32_t>(b[at + 2]) << 16) |
         (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
inline void put_u16(std::span<std::uint8_t> b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v);
  b[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
inline void put_u32(std::span<std::uint8_t> b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace rangefit::drivers::can
