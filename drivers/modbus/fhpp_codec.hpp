#pragma once
// Festo FHPP direct-mode telegrams (8 bytes each way) and their Modbus register images. Pure: no
// I/O, no logging; the transport (modbus_link) and the simulated drive (sim/) both use it.
// Layouts as implemented: docs/protocols/fhpp_modbus.md.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace rangefit::drivers::fhpp {

inline constexpr int kTelegramRegisters = 4;  // 8 bytes = 4 Modbus holding registers at address 0
using Registers = std::array<std::uint16_t, kTelegramRegisters>;

// Control byte CCON (host -> drive), bit masks.
enum Ccon : std::uint8_t {
  kCconEnable = 1u << 0,      // 1 = enable the drive
  kCconStop = 1u << 1,        // 1 = operation enabled, 0 = stop active (Festo polarity)
  kCconBrake = 1u << 2,       // 1 = release the brake
  kCconReset = 1u << 3,       // rising edge acknowledges a fault
  kCconLock = 1u << 5,        // 1 = lock out FCT/MMI control
  kCconModeDirect = 1u << 6,  // bits 6-7 operating mode: 01 = direct mode (setpoints in telegram)
};
// Control byte CPOS (host -> drive).
enum Cpos : std::uint8_t {
  kCposHalt = 1u << 0,   // 1 = halt NOT active, 0 = halt (Festo polarity)
  kCposStart = 1u << 1,  // rising edge starts the positioning task
  kCposHome = 1u << 2,   // rising edge starts homing
  kCposJogPlus = 1u << 3,
  kCposJogMinus = 1u << 4,
  kCposTeach = 1u << 5,
  kCposClear = 1u << 6,  // clear remaining path
};
// CDIR: bit 0 0 = absolute, 1 = relative; bits 1-2 control mode (0 = position).
enum Cdir : std::uint8_t { kCdirRelative = 1u << 0 };
// Status byte SCON (drive -> host).
enum Scon : std::uint8_t {
  kSconEnabled = 1u << 0,
  kSconOpen = 1u << 1,  // operation enabled
  kSconWarn = 1u << 2,
  kSconFault = 1u << 3,
  kSconLoadVoltage = 1u << 4,
  kSconFctMmi = 1u << 5,  // drive controlled by another master (FCT/MMI or another client)
  kSconModeDirect = 1u << 6,
};
// Status byte SPOS (drive -> host).
enum Spos : std::uint8_t {
  kSposHalt = 1u << 0,  // 1 = halt not active
  kSposAck = 1u << 1,   // start/home acknowledged (mirrors START/HOME after acceptance)
  kSposMotionComplete = 1u << 2,
  kSposTeach = 1u << 3,
  kSposMoving = 1u << 4,
  kSposFollowingError = 1u << 5,
  kSposStandstill = 1u << 6,
  kSposReferenced = 1u << 7,
};

// Host -> drive, direct mode.
struct OutputTelegram {
  std::uint8_t ccon = 0;
  std::uint8_t cpos = 0;
  std::uint8_t cdir = 0;
  std::uint8_t velocity_pct = 0;  // setpoint 1: speed in % of the drive's maximum speed
  std::int32_t position_inc = 0;  // setpoint 2: target position, increments
  bool operator==(const OutputTelegram&) const = default;
};

// Drive -> host, direct mode.
struct InputTelegram {
  std::uint8_t scon = 0;
  std::uint8_t spos = 0;
  std::uint8_t sdir = 0;
  std::uint8_t velocity_pct = 0;  // actual speed, % of maximum
  std::int32_t position_inc = 0;  // actual position, increments
  bool operator==(const InputTelegram&) const = default;
};

// How FHPP bytes map onto 16-bit registers. FHPP default: register k = byte 2k | byte 2k+1 << 8.
enum class ByteOrder : std::uint8_t { kLowByteFirst, kHighByteFirst };

using Bytes = std::array<std::uint8_t, 2 * kTelegramRegisters>;

Bytes to_bytes(const OutputTelegram& t);
Bytes to_bytes(const InputTelegram& t);
OutputTelegram output_from_bytes(const Bytes& b);
InputTelegram input_from_bytes(const Bytes& b);

Registers bytes_to_registers(const Bytes& b, ByteOrder order);
Bytes registers_to_bytes(const Registers& r, ByteOrder order);

Registers encode(const OutputTelegram& t, ByteOrder order);
Registers encode(const InputTelegram& t, ByteOrder order);
// Decoders take what arrived; fewer than kTelegramRegisters registers is a malformed reply.
std::optional<InputTelegram> decode_input(std::span<const std::uint16_t> regs, ByteOrder order);
std::optional<OutputTelegram> decode_output(std::span<const std::uint16_t> regs, ByteOrder order);

// Increments <-> mm for one axis (encoder resolution after gearing).
struct AxisScale {
  double increments_per_mm = 1000.0;  // increments per mm
  double max_speed_mm_s = 500.0;      // mm/s at velocity 100 %
  double to_mm(std::int32_t inc) const { return static_cast<double>(inc) / increments_per_mm; }
  // Rounds to the nearest increment; saturates at the int32 range.
  std::int32_t to_increments(double mm) const;
  double pct_to_mm_s(std::uint8_t pct) const { return max_speed_mm_s * pct / 100.0; }
  // Nearest whole percent in [1, 100]; 0 only for a non-positive speed.
  std::uint8_t mm_s_to_pct(double mm_s) const;
};

// "SCON=0x0b [ENABLED OPEN FAULT] SPOS=0x81 [HALT REF]": what a user reads in a refusal.
std::string describe_status(std::uint8_t scon, std::uint8_t spos);

}  // namespace rangefit::drivers::fhpp
