#pragma once
// CRC-32 (IEEE 802.3, reflected 0xEDB88320, init and final xor 0xFFFFFFFF), as zlib computes it;
// the CAN FD ranger profile and the CSS USB revolution frame both carry it.

#include <cstdint>
#include <span>

namespace rangefit::drivers {

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace rangefit::drivers
