#include "drivers/can/can_frame.hpp"

#include <algorithm>

namespace rangefit::drivers::can {

namespace {
constexpr std::array<std::uint8_t, 7> kFdSteps{12, 16, 20, 24, 32, 48, 64};

CanFrame fill(std::uint32_t id, std::span<const std::uint8_t> bytes, std::size_t capacity,
              std::uint8_t flags) {
  CanFrame f;
  f.id = id;
  f.flags = flags;
  const std::size_t n = std::min(bytes.size(), capacity);
  std::copy_n(bytes.begin(), n, f.data.begin());
  f.len = static_cast<std::uint8_t>(n);
  return f;
}
}  // namespace

std::uint8_t fd_padded_length(std::size_t n) {
  if (n <= 8) return static_cast<std::uint8_t>(n);
  for (std::uint8_t step : kFdSteps) {
    if (n <= step) return step;
  }
  return 64;
}

bool valid_fd_length(std::size_t n) { return n <= 64 && fd_padded_length(n) == n; }

CanFrame make_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) {
  return fill(id, bytes, 8, 0);
}

CanFrame make_fd_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) {
  CanFrame f = fill(id, bytes, CanFrame::kMaxData, kFrameFd | kFrameBrs);
  f.len = fd_padded_length(f.len);  // padding bytes stay zero
  return f;
}

}  // namespace rangefit::drivers::can
