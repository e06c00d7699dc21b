#include "drivers/can/cia402_codec.hpp"

#include <array>

namespace rangefit::drivers::can::cia402 {

namespace {
Message bad_length(Message m) {
  m.kind = Kind::kBadLength;
  return m;
}

CanFrame sdo_frame(std::uint32_t id, std::uint8_t cmd, std::uint16_t index, std::uint8_t sub,
                   std::uint32_t value) {
  std::array<std::uint8_t, 8> b{cmd, 0, 0, sub, 0, 0, 0, 0};
  put_u16(b, 1, index);
  put_u32(b, 4, value);
  return make_frame(id, b);
}
}  // namespace

Message decode(const CanFrame& f) {
  Message m;
  const auto d = f.payload();
  if (f.flags & (kFrameExtended | kFrameError | kFrameRtr | kFrameFd)) return m;
  const std::uint32_t fn = f.id & 0x780;
  const auto node = static_cast<std::uint8_t>(f.id & 0x7F);
  m.node = node;
  if (f.id == kNmtId) {
    m.kind = Kind::kNmt;
    if (d.size() != 2) return bad_length(m);
    m.nmt_command = d[0];
    m.node = d[1];
  } else if (f.id == kSyncId) {
    m.kind = Kind::kSync;
    if (d.size() > 1) return bad_length(m);
    m.sync_counter = d.empty() ? 0 : d[0];
  } else if (f.id == kTimeId) {
    m.kind = Kind::kTime;
    if (d.size() != 6) return bad_length(m);
  } else if (node == 0) {
    return m;  // function codes with node 0 are not used
  } else if (fn == 0x080) {
    m.kind = Kind::kEmcy;
    if (d.size() != 8) return bad_length(m);
    m.emcy_code = get_u16(d, 0);
    m.emcy_register = d[2];
  } else if (fn == 0x180) {
    m.kind = Kind::kTpdo1;
    if (d.size() != 6) return bad_length(m);
    m.statusword = get_u16(d, 0);
    m.position = static_cast<std::int32_t>(get_u32(d, 2));
  } else if (fn == 0x280) {
    m.kind = Kind::kTpdo2;
    if (d.size() != 4) return bad_length(m);
    m.velocity = static_cast<std::int32_t>(get_u32(d, 0));
  } else if (fn == 0x580 || fn == 0x600) {
    m.kind = fn == 0x580 ? Kind::kSdoResponse : Kind::kSdoRequest;
    if (d.size() != 8) return bad_length(m);
    m.sdo_command = d[0];
    m.sdo_index = get_u16(d, 1);
    m.sdo_subindex = d[3];
    m.sdo_data = get_u32(d, 4);
  } else if (fn == 0x700) {
    m.kind = Kind::kHeartbeat;
    if (d.size() != 1) return bad_length(m);
    m.nmt_state = d[0];
  }
  return m;
}

CanFrame encode_nmt(NmtCommand command, std::uint8_t node) {
  const std::array<std::uint8_t, 2> b{command, node};
  return make_frame(kNmtId, b);
}

CanFrame encode_sync(std::uint8_t counter) {
  const std::array<std::uint8_t, 1> b{counter};
  return make_frame(kSyncId, std::span(b.data(), counter == 0 ? 0 : 1));
}

CanFrame encode_tpdo1(std::uint8_t node, std::uint16_t statusword, std::int32_t position) {
  std::array<std::uint8_t, 6> b{};
  put_u16(b, 0, statusword);
  put_u32(b, 2, static_cast<std::uint32_t>(position));
  return make_frame(tpdo1_id(node), b);
}

CanFrame encode_tpdo2(std::uint8_t node, std::int32_t velocity) {
  std::array<std::uint8_t, 4> b{};
  put_u32(b, 0, static_cast<std::uint32_t>(velocity));
  return make_frame(tpdo2_id(node), b);
}

CanFrame encode_heartbeat(std::uint8_t node, NmtState state) {
  const std::array<std::uint8_t, 1> b{state};
  return make_frame(heartbeat_id(node), b);
}

CanFrame encode_emcy(std::uint8_t node, std::uint16_t code, std::uint8_t error_register) {
  std::array<std::uint8_t, 8> b{};
  put_u16(b, 0, code);
  b[2] = error_register;
  return make_frame(emcy_id(node), b);
}

CanFrame encode_sdo_download(std::uint8_t node, std::uint16_t index, std::uint8_t subindex,
                             std::uint32_t value, std::uint8_t size) {
  // ccs=1, expedited, size indicated; n = 4 - size unused bytes (CiA 301 7.2.4.3.3).
  const auto n = static_cast<std::uint8_t>(4 - (size < 1 ? 1 : size > 4 ? 4 : size));
  return sdo_frame(sdo_request_id(node), static_cast<std::uint8_t>(0x23 | (n << 2)), index,
                   subindex, value);
}

CanFrame encode_sdo_upload_request(std::uint8_t node, std::uint16_t index, std::uint8_t subindex) {
  return sdo_frame(sdo_request_id(node), kSdoUploadRequest, index, subindex, 0);
}

CanFrame encode_sdo_download_ok(std::uint8_t node, std::uint16_t index, std::uint8_t subindex) {
  return sdo_frame(sdo_response_id(node), kSdoDownloadOk, index, subindex, 0);
}

CanFrame encode_sdo_upload_reply(std::uint8_t node, std::uint16_t index, std::uint8_t subindex,
                                 std::uint32_t value) {
  return sdo_frame(sdo_response_id(node), 0x43, index, subindex, value);
}

CanFrame encode_sdo_abort(std::uint8_t node, std::uint16_t index, std::uint8_t subindex,
                          std::uint32_t abort_code) {
  return sdo_frame(sdo_response_id(node), kSdoAbort, index, subindex, abort_code);
}

}  // namespace rangefit::drivers::can::cia402
