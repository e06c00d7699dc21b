#include "drivers/can/linux_frame.hpp"

#include <algorithm>
#include <cstring>

namespace rangefit::drivers::can {

std::size_t to_linux(const CanFrame& in, canfd_frame& raw) {
  std::memset(&raw, 0, sizeof(raw));
  raw.can_id = in.id & ((in.flags & kFrameExtended) ? CAN_EFF_MASK : CAN_SFF_MASK);
  if (in.flags & kFrameExtended) raw.can_id |= CAN_EFF_FLAG;
  if (in.flags & kFrameRtr) raw.can_id |= CAN_RTR_FLAG;
  if (in.flags & kFrameError) raw.can_id |= CAN_ERR_FLAG;
  if (in.is_fd()) {
    raw.len = fd_padded_length(in.len);
    if (in.flags & kFrameBrs) raw.flags = CANFD_BRS;
    std::memcpy(raw.data, in.data.data(), raw.len);
    return CANFD_MTU;
  }
  raw.len = std::min<std::uint8_t>(in.len, CAN_MAX_DLEN);
  std::memcpy(raw.data, in.data.data(), raw.len);
  return CAN_MTU;
}

bool from_linux(const canfd_frame& raw, std::size_t nbytes, CanFrame& out) {
  if (nbytes != CAN_MTU && nbytes != CANFD_MTU) return false;
  const bool fd = nbytes == CANFD_MTU;
  out.flags = 0;
  if (fd) out.flags |= kFrameFd;
  if (fd && (raw.flags & CANFD_BRS)) out.flags |= kFrameBrs;
  if (raw.can_id & CAN_EFF_FLAG) out.flags |= kFrameExtended;
  if (raw.can_id & CAN_RTR_FLAG) out.flags |= kFrameRtr;
  if (raw.can_id & CAN_ERR_FLAG) out.flags |= kFrameError;
  out.id =
      raw.can_id & ((raw.can_id & (CAN_EFF_FLAG | CAN_ERR_FLAG)) ? CAN_EFF_MASK : CAN_SFF_MASK);
  out.len = std::min<std::uint8_t>(raw.len, fd ? CANFD_MAX_DLEN : CAN_MAX_DLEN);
  std::memcpy(out.data.data(), raw.data, out.len);
  return true;
}

}  // namespace rangefit::drivers::can
