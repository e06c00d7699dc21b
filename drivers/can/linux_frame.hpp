#pragma once
// Conversion between CanFrame and the kernel's struct canfd_frame, shared by the SocketCAN and
// in-process transports so both carry exactly the bytes the kernel would.

#include <linux/can.h>

#include <cstddef>
#include <cstdint>

#include "drivers/can/can_frame.hpp"

namespace rangefit::drivers::can {

// Fills raw and returns the number of bytes to write (CAN_MTU or CANFD_MTU).
std::size_t to_linux(const CanFrame& in, canfd_frame& raw);
// Converts nbytes read into raw; false for a size that is neither CAN_MTU nor CANFD_MTU.
bool from_linux(const canfd_frame& raw, std::size_t nbytes, CanFrame& out);

}  // namespace rangefit::drivers::can
