#include "drivers/modbus/fhpp_codec.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace rangefit::drivers::fhpp {
namespace {

void put_i32(Bytes& b, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int i = 0; i < 4; ++i) b[4 + i] = static_cast<std::uint8_t>(u >> (8 * i));  // low byte first
}

std::int32_t get_i32(const Bytes& b) {
  std::uint32_t u = 0;
  for (int i = 0; i < 4; ++i) u |= static_cast<std::uint32_t>(b[4 + i]) << (8 * i);
  return static_cast<std::int32_t>(u);
}

void append_bits(std::string& s, std::uint8_t value, const char* const names[8]) {
  s += " [";
  bool first = true;
  for (int i = 0; i < 8; ++i) {
    if (!(value & (1u << i)) || names[i][0] == '\0') continue;
    if (!first) s += ' ';
    s += names[i];
    first = false;
  }
  s += ']';
}

}  // namespace

Bytes to_bytes(const OutputTelegram& t) {
  Bytes b{t.ccon, t.cpos, t.cdir, t.velocity_pct, 0, 0, 0, 0};
  put_i32(b, t.position_inc);
  return b;
}

Bytes to_bytes(const InputTelegram& t) {
  Bytes b{t.scon, t.spos, t.sdir, t.velocity_pct, 0, 0, 0, 0};
  put_i32(b, t.position_inc);
  return b;
}

OutputTelegram output_from_bytes(const Bytes& b) { return {b[0], b[1], b[2], b[3], get_i32(b)}; }
InputTelegram input_from_bytes(const Bytes& b) { return {b[0], b[1], b[2], b[3], get_i32(b)}; }

Registers bytes_to_registers(const Bytes& b, ByteOrder order) {
  Registers r{};
  for (int k = 0; k < kTelegramRegisters; ++k) {
    const unsigned lo = order == ByteOrder::kLowByteFirst ? b[2 * k] : b[2 * k + 1];
    const unsigned hi = order == ByteOrder::kLowByteFirst ? b[2 * k + 1] : b[2 * k];
    r[k] = static_cast<std::uint16_t>(lo | (hi << 8));
  }
  return r;
}

Bytes registers_to_bytes(const Registers& r, ByteOrder order) {
  Bytes b{};
  for (int k = 0; k < kTelegramRegisters; ++k) {
    const auto lo = static_cast<std::uint8_t>(r[k] & 0xFFu);
    const auto hi = static_cast<std::uint8_t>(r[k] >> 8);
    b[2 * k] = order == ByteOrder::kLowByteFirst ? lo : hi;
    b[2 * k + 1] = order == ByteOrder::kLowByteFirst ? hi : lo;
  }
  return b;
}

Registers encode(const OutputTelegram& t, ByteOrder order) {
  return bytes_to_registers(to_bytes(t), order);
}
Registers encode(const InputTelegram& t, ByteOrder order) {
  return bytes_to_registers(to_bytes(t), order);
}

std::optional<InputTelegram> decode_input(std::span<const std::uint16_t> regs, ByteOrder order) {
  if (regs.size() < kTelegramRegisters) return std::nullopt;
  Registers r{};
  for (int k = 0; k < kTelegramRegisters; ++k) r[k] = regs[k];
  return input_from_bytes(registers_to_bytes(r, order));
}

std::optional<OutputTelegram> decode_output(std::span<const std::uint16_t> regs, ByteOrder order) {
  if (regs.size() < kTelegramRegisters) return std::nullopt;
  Registers r{};
  for (int k = 0; k < kTelegramRegisters; ++k) r[k] = regs[k];
  return output_from_bytes(registers_to_bytes(r, order));
}

std::int32_t AxisScale::to_increments(double mm) const {
  const double inc = std::round(mm * increments_per_mm);
  if (!(inc > std::numeric_limits<std::int32_t>::min()))
    return std::numeric_limits<std::int32_t>::min();
  if (inc >= std::numeric_limits<std::int32_t>::max())
    return std::numeric_limits<std::int32_t>::max();
  return static_cast<std::int32_t>(inc);
}

std::uint8_t AxisScale::mm_s_to_pct(double mm_s) const {
  if (!(mm_s > 0.0) || !(max_speed_mm_s > 0.0)) return 0;
  const double pct = std::round(100.0 * mm_s / max_speed_mm_s);
  if (pct < 1.0) return 1;
  if (pct > 100.0) return 100;
  return static_cast<std::uint8_t>(pct);
}

std::string describe_status(std::uint8_t scon, std::uint8_t spos) {
  static const char* const kScon[8] = {"ENABLED", "OPEN",    "WARN",   "FAULT",
                                       "VLOAD",   "FCT/MMI", "DIRECT", ""};
  static const char* const kSpos[8] = {"HALT", "ACK", "MC", "TEACH", "MOV", "DEV", "STILL", "REF"};
  char buf[32];
  std::snprintf(buf, sizeof buf, "SCON=0x%02x", scon);
  std::string s = buf;
  append_bits(s, scon, kScon);
  std::snprintf(buf, sizeof buf, " SPOS=0x%02x", spos);
  s += buf;
  append_bits(s, spos, kSpos);
  return s;
}

}  // namespace rangefit::drivers::fhpp
