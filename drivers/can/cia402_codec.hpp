#pragma once
// CANopen CiA 301/402 messages used by the joint drivers: NMT, SYNC with counter, EMCY, TPDO1
// (statusword 0x6041 + position actual value 0x6064), TPDO2 (velocity actual value 0x606C),
// expedited SDO, heartbeat. Pure encode/decode on CanFrame; no transport, no state.

#include <cstdint>
#include <optional>

#include "drivers/can/can_frame.hpp"

namespace rangefit::drivers::can::cia402 {

inline constexpr std::uint32_t kNmtId = 0x000;
inline constexpr std::uint32_t kSyncId = 0x080;
inline constexpr std::uint32_t kTimeId = 0x100;
inline constexpr std::uint32_t emcy_id(std::uint8_t node) { return 0x080u + node; }
inline constexpr std::uint32_t tpdo1_id(std::uint8_t node) { return 0x180u + node; }
inline constexpr std::uint32_t tpdo2_id(std::uint8_t node) { return 0x280u + node; }
inline constexpr std::uint32_t sdo_response_id(std::uint8_t node) { return 0x580u + node; }
inline constexpr std::uint32_t sdo_request_id(std::uint8_t node) { return 0x600u + node; }
inline constexpr std::uint32_t heartbeat_id(std::uint8_t node) { return 0x700u + node; }

enum NmtCommand : std::uint8_t {
  kNmtStart = 0x01,
  kNmtStop = 0x02,
  kNmtPreOperational = 0x80,
  kNmtResetNode = 0x81,
  kNmtResetCommunication = 0x82,
};

enum NmtState : std::uint8_t {
  kBootUp = 0x00,
  kStopped = 0x04,
  kOperational = 0x05,
  kPreOperational = 0x7F,
};

// Statusword bits the driver cares about (CiA 402 state machine).
inline constexpr std::uint16_t kStatusFault = 1u << 3;
inline constexpr std::uint16_t kStatusOperationEnabled = 0x0027;  // mask 0x006F

enum class Kind : std::uint8_t {
  kNmt,
  kSync,
  kTime,
  kEmcy,
  kTpdo1,
  kTpdo2,
  kSdoRequest,
  kSdoResponse,
  kHeartbeat,
  kUnknown,    // id outside the CiA 402 layout this codec speaks
  kBadLength,  // known id, wrong data length
};

struct Message {
  Kind kind = Kind::kUnknown;
  std::uint8_t node = 0;          // 1..127; 0 for NMT/SYNC/TIME
  std::uint8_t sync_counter = 0;  // SYNC: 0 when the SYNC carries no counter
  std::uint8_t nmt_command = 0;   // NMT
  std::uint8_t nmt_state = 0;     // heartbeat
  std::uint16_t statusword = 0;   // TPDO1
  std::int32_t position = 0;      // TPDO1, increments
  std::int32_t velocity = 0;      // TPDO2, increments/s
  std::uint16_t emcy_code = 0;    // EMCY (0 = error reset)
  std::uint8_t emcy_register = 0;
  std::uint8_t sdo_command = 0;  // SDO command specifier byte
  std::uint16_t sdo_index = 0;
  std::uint8_t sdo_subindex = 0;
  std::uint32_t sdo_data = 0;  // expedited value, or abort code
};

Message decode(const CanFrame& frame);

CanFrame encode_nmt(NmtCommand command, std::uint8_t node /* 0 = all */);
CanFrame encode_sync(std::uint8_t counter /* 0 = no counter byte */);
CanFrame encode_tpdo1(std::uint8_t node, std::uint16_t statusword, std::int32_t position);
CanFrame encode_tpdo2(std::uint8_t node, std::int32_t velocity);
CanFrame encode_heartbeat(std::uint8_t node, NmtState state);
CanFrame encode_emcy(std::uint8_t node, std::uint16_t code, std::uint8_t error_register);
// Expedited SDO download of `size` (1..4) bytes; the server answers 0x60 or an abort (0x80).
CanFrame encode_sdo_download(std::uint8_t node, std::uint16_t index, std::uint8_t subindex,
                             std::uint32_t value, std::uint8_t size);
CanFrame encode_sdo_upload_request(std::uint8_t node, std::uint16_t index, std::uint8_t subindex);
// Server side answers: download confirmation, expedited upload (4 bytes) or abort.
CanFrame encode_sdo_download_ok(std::uint8_t node, std::uint16_t index, std::uint8_t subindex);
CanFrame encode_sdo_upload_reply(std::uint8_t node, std::uint16_t index, std::uint8_t subindex,
                                 std::uint32_t value);
CanFrame encode_sdo_abort(std::uint8_t node, std::uint16_t index, std::uint8_t subindex,
                          std::uint32_t abort_code);

inline constexpr std::uint8_t kSdoDownloadOk = 0x60;
inline constexpr std::uint8_t kSdoAbort = 0x80;
inline constexpr std::uint8_t kSdoUploadRequest = 0x40;
inline bool sdo_is_download_request(std::uint8_t cmd) { return (cmd & 0xE0) == 0x20; }
inline bool sdo_is_upload_reply(std::uint8_t cmd) { return (cmd & 0xE0) == 0x40 && cmd != 0x40; }

// SYNC counter that follows `counter` for an overflow value of 0x1019 (1..overflow).
inline std::uint8_t next_sync_counter(std::uint8_t counter, std::uint8_t overflow) {
  return counter >= overflow ? 1 : static_cast<std::uint8_t>(counter + 1);
}

}  // namespace rangefit::drivers::can::cia402
