#pragma once
// CRC-32 (IEEE 802.3, reflected 0xEDB88320, init and final xor 0xFFFFFFFF), as zlib computes it;
// the ranger profile carries it over its range data.

#include <cstdint>
#include <span>

namespace rangefit::drivers::can {

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace rangefit::drivers::can
