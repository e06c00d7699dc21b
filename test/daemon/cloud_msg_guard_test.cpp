#include "daemon/dds/cloud_msg_guard.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <vector>

namespace rangefit::daemon {
namespace cloud_msg_guard_test {

TEST(CloudMsgGuard, SizesAreCheckedWithoutOverflow) {
  EXPECT_TRUE(cloud_msg_fits(4, 2, 12, 96));
  EXPECT_FALSE(cloud_msg_fits(4, 2, 12, 95));
  EXPECT_TRUE(cloud_msg_fits(0, 7, 0, 0));
  EXPECT_FALSE(cloud_msg_fits(1, 1, 0, 1000));
  // 2^31 * 2^31 * 16 = 2^66 wraps to 0 in 64 bits, which "fits" any data.
  EXPECT_FALSE(cloud_msg_fits(1u << 31, 1u << 31, 16, 0));
  EXPECT_FALSE(cloud_msg_fits(UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT64_MAX / 2));
}

TEST(CloudMsgGuard, AHostileCloudDecodesToAnEmptyCloudInsteadOfThrowing) {
  // A real cloud of two points, as the daemon publishes it, then its width and height inflated.
  PointCloud cloud;
  cloud.frame_id = "world";
  cloud.points = {{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}};
  const CloudOut out(cloud);
  sensor_msgs_msg_dds__PointCloud2_ msg = out.msg();
  EXPECT_EQ(cloud_from_wire(msg).points.size(), 2u);
  msg.width = 1u << 31;
  msg.height = 1u << 31;
  PointCloud hostile;
  EXPECT_NO_THROW(hostile = cloud_from_wire(msg));
  EXPECT_TRUE(hostile.points.empty());
  EXPECT_EQ(hostile.frame_id, "world");
}

// FLOAT64 metres near the double's limit are finite on the wire but not in mm (x 1000): such a
// point is dropped like a NaN one, so a decoded cloud holds finite points only (the input the
// dds_messages fuzzer found).
TEST(CloudMsgGuard, APointFiniteInMetresButNotInMillimetresIsDropped) {
  const double points[2][3] = {{1e308, 0.0, 0.0}, {0.5, -0.25, 2.0}};  // metres
  std::vector<std::uint8_t> data(sizeof points);
  std::memcpy(data.data(), points, sizeof points);
  char x[] = "x", y[] = "y", z[] = "z";
  sensor_msgs_msg_dds__PointField_ fields[3] = {{x, 0, 8, 1}, {y, 8, 8, 1}, {z, 16, 8, 1}};
  char frame[] = "world";
  sensor_msgs_msg_dds__PointCloud2_ msg{};
  msg.header.frame_id = frame;
  msg.height = 1;
  msg.width = 2;
  msg.fields = {3, 3, fields, false};
  msg.is_bigendian = std::endian::native == std::endian::big;
  msg.point_step = 24;
  msg.row_step = 48;
  msg.data = {48, 48, data.data(), false};
  const PointCloud cloud = cloud_from_wire(msg);
  ASSERT_EQ(cloud.points.size(), 1u);
  EXPECT_TRUE(cloud.points[0].allFinite());
  EXPECT_NEAR(cloud.points[0].x(), 500.0, 1e-9);  // mm
  EXPECT_NEAR(cloud.points[0].z(), 2000.0, 1e-9);
}

}  // namespace cloud_msg_guard_test
}  // namespace rangefit::daemon
