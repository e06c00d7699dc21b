#include "daemon/dds/cloud_msg_guard.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rangefit::daemon {
namespace {

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

}  // namespace
}  // namespace rangefit::daemon
