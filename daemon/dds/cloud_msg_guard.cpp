#include "daemon/dds/cloud_msg_guard.hpp"

namespace rangefit::daemon {

bool cloud_msg_fits(std::uint32_t width, std::uint32_t height, std::uint32_t point_step,
                    std::uint64_t data_length) {
  const std::uint64_t points = std::uint64_t{width} * height;  // < 2^64: no overflow
  if (points == 0) return true;
  if (point_step == 0) return false;
  return points <= data_length / point_step;
}

PointCloud cloud_from_wire(const sensor_msgs_msg_dds__PointCloud2_& msg) {
  if (!cloud_msg_fits(msg.width, msg.height, msg.point_step, msg.data._length)) {
    PointCloud empty;
    if (msg.header.frame_id != nullptr) empty.frame_id = msg.header.frame_id;
    return empty;
  }
  return from_msg(msg);
}

}  // namespace rangefit::daemon
