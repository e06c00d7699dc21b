#pragma once
// Schunk/AMTEC PowerCube (M5) messages used by the polled joint driver: position read request
// (GET 0x0C0+id [0x0A 0x62]) and its reply (0x0A0+id [0x0A 0x62 float32 pos, state, DIO]),
// plus the broadcast commands. Pure encode/decode; ids 1..31.

#include <cstdint>
#include <optional>

#include "drivers/can/can_frame.hpp"

namespace rangefit::drivers::can::powercube {

inline constexpr std::uint8_t kMaxModule = 31;
inline constexpr std::uint32_t kBroadcastId = 0x100;
inline constexpr std::uint32_t get_id(std::uint8_t module) { return 0x0C0u + module; }
inline constexpr std::uint32_t set_id(std::uint8_t module) { return 0x0E0u + module; }
inline constexpr std::uint32_t reply_id(std::uint8_t module) { return 0x0A0u + module; }

inline constexpr std::uint8_t kCmdGetExtended = 0x0A;
inline constexpr std::uint8_t kParamPosition = 0x62;

enum ShortState : std::uint8_t {
  kStateNotOk = 0x01,
  kStateHome = 0x02,
  kStateLimitLow = 0x04,
  kStateLimitHigh = 0x08,
  kStateMoving = 0x10,
  kStateRampEnd = 0x20,
  kStateStepInProgress = 0x40,
  kStateStepBufferFull = 0x80,
};

enum BroadcastCommand : std::uint8_t {
  kBroadcastReset = 0x00,
  kBroadcastHome = 0x01,
  kBroadcastHalt = 0x02,
  kBroadcastWatchdogRefresh = 0x07,
};

struct PositionReply {
  std::uint8_t module = 0;
  float position_rad = 0.0F;
  std::uint8_t state = 0;  // ShortState bits
  std::uint8_t dio = 0;
};

enum class Kind : std::uint8_t { kPositionRequest, kPositionReply, kBroadcast, kOther, kBadLength };

struct Message {
  Kind kind = Kind::kOther;
  std::uint8_t module = 0;
  PositionReply reply;         // kPositionReply
  std::uint8_t broadcast = 0;  // kBroadcast
};

Message decode(const CanFrame& frame);

CanFrame encode_position_request(std::uint8_t module);
CanFrame encode_position_reply(const PositionReply& reply);
CanFrame encode_broadcast(BroadcastCommand command);

}  // namespace rangefit::drivers::can::powercube
