#include "drivers/usb/css_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace rangefit::drivers::css_usb {
namespace {

template <typename T>
void put(std::vector<std::uint8_t>& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i)));
  }
}

template <typename T>
T get(const std::uint8_t* bytes) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) value |= std::uint64_t{bytes[i]} << (8 * i);
  return static_cast<T>(value);
}

}  // namespace

void encode_revolution(const WireRevolution& revolution, std::vector<std::uint8_t>& out) {
  const std::size_t start = out.size();
  out.reserve(start + kFrameBytes);
  out.insert(out.end(), kMagic.begin(), kMagic.end());
  put(out, revolution.sequence);
  put(out, revolution.device_time_us);
  put(out, revolution.period_us);
  put(out, static_cast<std::uint16_t>(kSamples));
  put(out, revolution.flags);
  for (const WireSample& s : revolution.samples) {
    put(out, s.range_um);
    out.push_back(s.intensity);
    out.push_back(s.quality);
  }
  put(out, crc32(std::span(out).subspan(start, kCrcOffset)));
}

std::optional<WireRevolution> decode_revolution(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kFrameBytes || !std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) {
    return std::nullopt;
  }
  const std::uint8_t* p = bytes.data();
  if (get<std::uint16_t>(p + 20) != kSamples) return std::nullopt;
  if (get<std::uint32_t>(p + kCrcOffset) != crc32(bytes.first(kCrcOffset))) return std::nullopt;
  WireRevolution r;
  r.sequence = get<std::uint32_t>(p + 4);
  r.device_time_us = get<std::uint64_t>(p + 8);
  r.period_us = get<std::uint32_t>(p + 16);
  r.flags = get<std::uint16_t>(p + 22);
  const std::uint8_t* s = p + kHeaderBytes;
  for (std::size_t i = 0; i < kSamples; ++i, s += kSampleBytes) {
    r.samples[i] = {get<std::uint16_t>(s), s[2], s[3]};
  }
  return r;
}

std::array<std::uint8_t, kInfoBytes> encode_info(const DeviceInfo& info) {
  std::vector<std::uint8_t> out(16, 0);
  std::memcpy(out.data(), info.serial.data(), std::min<std::size_t>(16, info.serial.size()));
  put(out, info.firmware);
  put(out, info.samples_per_revolution);
  put(out, info.rate_centi_hz);
  put(out, info.scan_diameter_um);
  put(out, info.standoff_min_um);
  put(out, info.standoff_max_um);
  std::array<std::uint8_t, kInfoBytes> bytes{};
  std::copy(out.begin(), out.end(), bytes.begin());
  return bytes;
}

std::optional<DeviceInfo> decode_info(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kInfoBytes) return std::nullopt;
  const std::uint8_t* p = bytes.data();
  DeviceInfo info;
  const auto serial_end = std::find(p, p + 16, std::uint8_t{0});
  info.serial.assign(p, serial_end);
  info.firmware = get<std::uint32_t>(p + 16);
  info.samples_per_revolution = get<std::uint16_t>(p + 20);
  info.rate_centi_hz = get<std::uint16_t>(p + 22);
  info.scan_diameter_um = get<std::uint32_t>(p + 24);
  info.standoff_min_um = get<std::uint32_t>(p + 28);
  info.standoff_max_um = get<std::uint32_t>(p + 32);
  return info;
}

float range_mm(std::uint16_t range_um) {
  if (range_um == kNoReturn) return std::numeric_limits<float>::quiet_NaN();
  return static_cast<float>(kRangeOffsetMm + range_um * 1e-3);
}

std::uint16_t range_um(float range_mm) {
  const double um = std::round((static_cast<double>(range_mm) - kRangeOffsetMm) * 1e3);
  if (!(um >= 0.0 && um < kNoReturn)) return kNoReturn;  // also NaN
  return static_cast<std::uint16_t>(um);
}

}  // namespace rangefit::drivers::css_usb
