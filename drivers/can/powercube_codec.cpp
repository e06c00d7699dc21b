#include "drivers/can/powercube_codec.hpp"

#include <array>
#include <bit>

namespace rangefit::drivers::can::powercube {

Message decode(const CanFrame& f) {
  Message m;
  if (f.flags & (kFrameExtended | kFrameError | kFrameRtr | kFrameFd)) return m;
  const auto d = f.payload();
  if (f.id == kBroadcastId) {
    m.kind = Kind::kBroadcast;
    if (d.size() != 1)
      m.kind = Kind::kBadLength;
    else
      m.broadcast = d[0];
    return m;
  }
  const auto module = static_cast<std::uint8_t>(f.id & 0x1F);
  const std::uint32_t base = f.id & ~0x1Fu;
  if (module == 0 || (base != 0x0A0 && base != 0x0C0)) return m;
  m.module = module;
  const bool position = d.size() >= 2 && d[0] == kCmdGetExtended && d[1] == kParamPosition;
  if (base == 0x0C0) {
    if (!position) return m;  // other GET parameters are not ours
    m.kind = d.size() == 2 ? Kind::kPositionRequest : Kind::kBadLength;
    return m;
  }
  if (!position) return m;
  if (d.size() != 8) {
    m.kind = Kind::kBadLength;
    return m;
  }
  m.kind = Kind::kPositionReply;
  m.reply.module = module;
  m.reply.position_rad = std::bit_cast<float>(get_u32(d, 2));
  m.reply.state = d[6];
  m.reply.dio = d[7];
  return m;
}

CanFrame encode_position_request(std::uint8_t module) {
  const std::array<std::uint8_t, 2> b{kCmdGetExtended, kParamPosition};
  return make_frame(get_id(module), b);
}

CanFrame encode_position_reply(const PositionReply& r) {
  std::array<std::uint8_t, 8> b{kCmdGetExtended, kParamPosition};
  put_u32(b, 2, std::bit_cast<std::uint32_t>(r.position_rad));
  b[6] = r.state;
  b[7] = r.dio;
  return make_frame(reply_id(r.module), b);
}

CanFrame encode_broadcast(BroadcastCommand command) {
  const std::array<std::uint8_t, 1> b{command};
  return make_frame(kBroadcastId, b);
}

}  // namespace rangefit::drivers::can::powercube
