#pragma once
// Circular Scanning Sensor USB protocol (project-defined; layouts in docs/protocols/css_usb.md).
// Pure codec: no I/O, no logging. The driver decodes with it, simulated devices encode with it.
//
// One revolution = one bulk IN transfer of kFrameBytes, little-endian:
//   0  magic "CSS1"            4  sequence U32          8  device time at index pulse U64 us
//   16 period U32 us           20 n U16 (= 512)         22 flags U16 (hal::CssFlags bits)
//   24 512 x {range U16 um above 65 mm (0xFFFF = no return), intensity U8, quality U8}
//   2072 CRC-32 (IEEE 802.3, as zlib's crc32) of bytes 0..2071

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "drivers/common/crc32.hpp"

namespace rangefit::drivers::css_usb {

inline constexpr std::array<std::uint8_t, 4> kMagic = {'C', 'S', 'S', '1'};
inline constexpr std::size_t kSamples = 512;
inline constexpr std::size_t kHeaderBytes = 24;
inline constexpr std::size_t kSampleBytes = 4;
inline constexpr std::size_t kCrcOffset = kHeaderBytes + kSamples * kSampleBytes;  // 2072
inline constexpr std::size_t kFrameBytes = kCrcOffset + 4;                         // 2076
inline constexpr std::uint16_t kNoReturn = 0xFFFF;
inline constexpr double kRangeOffsetMm = 65.0;  // range 0 um on the wire = 65 mm

// Vendor control requests on interface 0 (bmRequestType vendor | interface).
enum class Request : std::uint8_t {
  kGetInfo = 0x01,  // IN, kInfoBytes
  kStart = 0x02,    // OUT, no data
  kStop = 0x03,     // OUT, no data
  kSetRate = 0x04,  // OUT, wValue = revolutions per second x 100
  kGetTime = 0x05,  // IN, 8 bytes: device us counter U64
};

struct WireSample {
  std::uint16_t range_um = kNoReturn;  // um above kRangeOffsetMm
  std::uint8_t intensity = 0;
  std::uint8_t quality = 0;
};

struct WireRevolution {
  std::uint32_t sequence = 0;
  std::uint64_t device_time_us = 0;  // device us counter at the index pulse (may wrap, see clock)
  std::uint32_t period_us = 0;
  std::uint16_t flags = 0;
  std::array<WireSample, kSamples> samples{};
};

// GET_INFO reply, kInfoBytes little-endian: serial char[16] (NUL padded), firmware U32,
// samples per revolution U16, rate U16 (rev/s x 100), scan diameter U32 um, standoff min U32 um,
// standoff max U32 um.
inline constexpr std::size_t kInfoBytes = 36;
struct DeviceInfo {
  std::string serial;
  std::uint32_t firmware = 0;
  std::uint16_t samples_per_revolution = kSamples;
  std::uint16_t rate_centi_hz = 700;
  std::uint32_t scan_diameter_um = 27000;
  std::uint32_t standoff_min_um = 65000;
  std::uint32_t standoff_max_um = 130000;
};

// Appends one frame (kFrameBytes) to out.
void encode_revolution(const WireRevolution& revolution, std::vector<std::uint8_t>& out);
// Decodes a frame that starts at bytes[0]; nullopt unless magic, n and CRC are right.
std::optional<WireRevolution> decode_revolution(std::span<const std::uint8_t> bytes);

std::array<std::uint8_t, kInfoBytes> encode_info(const DeviceInfo& info);
std::optional<DeviceInfo> decode_info(std::span<const std::uint8_t> bytes);

// Range conversions: mm (NaN = no return) <-> wire um above 65 mm. Ranges outside
// [65, 130.534] mm encode as no return.
float range_mm(std::uint16_t range_um);
std::uint16_t range_um(float range_mm);

}  // namespace rangefit::drivers::css_usb
