#include "drivers/common/crc32.hpp"

#include <zlib.h>

#include <limits>

namespace rangefit::drivers {

// zlib's crc32 is the same CRC (and faster than a byte table: it folds several bytes a step).
// It takes the length as uInt, so spans beyond 4 GiB are fed in pieces.
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  uLong c = crc;
  constexpr std::size_t kMaxPiece = std::numeric_limits<uInt>::max();
  while (!bytes.empty()) {
    const std::size_t n = bytes.size() < kMaxPiece ? bytes.size() : kMaxPiece;
    c = ::crc32(c, bytes.data(), static_cast<uInt>(n));
    bytes = bytes.subspan(n);
  }
  return static_cast<std::uint32_t>(c);
}

}  // namespace rangefit::drivers
