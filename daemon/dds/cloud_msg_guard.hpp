#pragma once
// A PointCloud2 from the wire is hostile input: width and height are 32-bit each, so
// width * height * point_step can exceed 64 bits and wrap to a small number that passes a plain
// "enough data?" check (2^31 x 2^31 points made `rangefit watch` exit in reserve()). These check
// the sizes without overflow before anything is decoded or reserved.

#include <cstdint>

#include "daemon/dds/messages.hpp"

namespace rangefit::daemon {

// True when width * height points of point_step bytes fit in data_length bytes.
bool cloud_msg_fits(std::uint32_t width, std::uint32_t height, std::uint32_t point_step,
                    std::uint64_t data_length);

// from_msg() for clouds whose sizes fit their data; an empty cloud (with the frame) otherwise,
// as from_msg answers other malformed clouds.
PointCloud cloud_from_wire(const sensor_msgs_msg_dds__PointCloud2_& msg);

}  // namespace rangefit::daemon
