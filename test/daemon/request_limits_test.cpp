// Bounds on what a DDS message can make the daemon do: a request's sweep (it decides the scan's
// point count) and a PointCloud2 whose sizes overflow 64 bits when multiplied.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "daemon/dds/messages.hpp"
#include "daemon/service/request_validation.hpp"

namespace rangefit::daemon {
namespace request_limits_test {

DaemonConfig css_and_stripe() {
  DaemonConfig c;
  for (const char* kind : {"css", "stripe"}) {
    DeviceConfig d;
    d.name = d.kind = kind;
    c.devices.push_back(d);
  }
  c.service.bore_sensor = "css";
  return c;
}

ScanRequest bore_sweep(const std::string& sensor, double start, double end, double speed) {
  ScanRequest r;
  r.id = "sweep";
  r.bore.radius_mm = 5;
  r.sensor = sensor;
  r.sweep_start = start;
  r.sweep_end = end;
  r.sweep_speed = speed;
  return r;
}

TEST(RequestLimits, SweepsBeyondOneTurnOrTenMetresAreRefused) {
  const DaemonConfig config = css_and_stripe();
  ScanRequest huge_css = bore_sweep("css", -30, 30, 1);  // rad
  EXPECT_NE(validate_request(huge_css, config).find("one turn"), std::string::npos);
  ScanRequest absurd = bore_sweep("css", -1e15, 1e15, 1);
  EXPECT_FALSE(validate_request(absurd, config).empty());
  ScanRequest fast = bore_sweep("css", 0, 1, 1e6);
  EXPECT_NE(validate_request(fast, config).find("sweep_speed"), std::string::npos);
  ScanRequest long_stripe = bore_sweep("stripe", 0, 20, 0.1);  // metres on the wire
  EXPECT_NE(validate_request(long_stripe, config).find("10 m"), std::string::npos);
  ScanRequest turn = bore_sweep("css", -3.1, 3.1, 1);
  EXPECT_EQ(validate_request(turn, config), "");
  ScanRequest stripe = bore_sweep("stripe", 0, 0.5, 0.05);
  EXPECT_EQ(validate_request(stripe, config), "");
}

TEST(RequestLimits, CloudWhosePointCountTimesStepWrapsAroundIsNoCloud) {
  char x[] = "x", y[] = "y", z[] = "z", frame[] = "world";
  sensor_msgs_msg_dds__PointField_ fields[3] = {{x, 0, 7, 1}, {y, 4, 7, 1}, {z, 8, 7, 1}};
  std::vector<std::uint8_t> data(64);
  sensor_msgs_msg_dds__PointCloud2_ msg{};
  msg.header.frame_id = frame;
  msg.height = 1u << 31;
  msg.width = 1u << 31;  // 2^62 points of 16 bytes: 2^66, which wraps to 0
  msg.fields = {3, 3, fields, false};
  msg.point_step = 16;
  msg.row_step = 0;
  msg.data = {static_cast<std::uint32_t>(data.size()), static_cast<std::uint32_t>(data.size()),
              data.data(), false};
  PointCloud cloud;
  EXPECT_NO_THROW(cloud = from_msg(msg));
  EXPECT_TRUE(cloud.empty());
  EXPECT_EQ(cloud.frame_id, "world");
  msg.height = msg.width = 2;  // four points in 64 bytes: a cloud
  EXPECT_EQ(from_msg(msg).size(), 4u);
}

}  // namespace request_limits_test
}  // namespace rangefit::daemon
