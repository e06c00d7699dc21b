// What a driver = "real" device's [[devices]] table hands its drivers: the configured bus
// addresses reach the driver settings (and the CAN filters built from them), unset ones stay at
// the drivers' own defaults. No bus needed.
#include "daemon/cell/driver_configs.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace rangefit::daemon {
namespace driver_configs_test {

DeviceConfig device(const std::string& kind, const std::string& transport) {
  DeviceConfig d;
  d.name = "dev";
  d.kind = kind;
  d.driver = DriverKind::kReal;
  d.transport = transport;
  return d;
}

TEST(DriverConfigs, ConfiguredNodesReachTheCanDriversAndTheirFilters) {
  DeviceConfig robot = device("robot", "can0");
  robot.can_node = 9;
  const auto joints = robot_joint_config(robot, 6);
  ASSERT_EQ(joints.joints.size(), 1u);
  EXPECT_EQ(joints.joints[0].node, 9);
  EXPECT_EQ(joints.joints[0].joint, 6);
  EXPECT_TRUE(drivers::can::cia402_filter(joints).accepts(0x180 + 9));  // its TPDO1
  EXPECT_FALSE(drivers::can::cia402_filter(joints).accepts(0x180 + 1)) << "not the default node";

  DeviceConfig head = device("pan_tilt", "can0");
  head.can_node = 40;
  head.pan_node = 21;
  head.tilt_node = 22;
  EXPECT_EQ(ranger_config(head, {}).node, 40);
  EXPECT_TRUE(drivers::can::ranger_filter(ranger_config(head, {})).accepts(0x380 + 40));
  const auto bus = drivers::can::pan_tilt_bus_config(pan_tilt_config(head));
  ASSERT_EQ(bus.joints.size(), 2u);
  EXPECT_EQ(bus.joints[0].node, 21);
  EXPECT_EQ(bus.joints[1].node, 22);
  EXPECT_EQ(bus.name, "dev/angles");
}

TEST(DriverConfigs, UnsetAddressesKeepTheDriversDefaults) {
  EXPECT_EQ(robot_joint_config(device("robot", "can0"), 6).joints.at(0).node,
            drivers::can::Cia402JointConfig{}.node);
  EXPECT_EQ(ranger_config(device("stripe", "can0"), {}).node, drivers::can::RangerConfig{}.node);
  const auto head = pan_tilt_config(device("pan_tilt", "can0"));
  EXPECT_EQ(head.pan.node, drivers::can::PanTiltConfig{}.pan.node);
  EXPECT_EQ(head.tilt.node, drivers::can::PanTiltConfig{}.tilt.node);
  EXPECT_EQ(fhpp_axis_config(device("axis", "10.0.0.5:502"), 400).link.unit_id,
            drivers::ModbusLinkConfig{}.unit_id);
}

TEST(DriverConfigs, TheRangerReadsItsColumnsOnTheFanOfTheConfiguredGeometry) {
  // The real ranger's points must land where fusion and the simulator put them: on the fan
  // rays of [fusion.stripe_cell.ranger] (or the head's), not on parallel columns.
  hal::StripeRanger geometry;
  geometry.fan_angle_rad = 0.4;
  EXPECT_DOUBLE_EQ(ranger_config(device("stripe", "can0"), geometry).fan_angle_rad, 0.4);
  EXPECT_DOUBLE_EQ(ranger_config(device("pan_tilt", "can0"), hal::StripeRanger{}).fan_angle_rad,
                   hal::StripeRanger{}.fan_angle_rad);
}

TEST(DriverConfigs, AxisGetsItsUnitAddressAndTravel) {
  DeviceConfig axis = device("axis", "10.0.0.5:1502");
  axis.modbus_unit = 17;
  const auto c = fhpp_axis_config(axis, 350.0);
  EXPECT_EQ(c.link.unit_id, 17);
  EXPECT_EQ(c.link.host, "10.0.0.5");
  EXPECT_EQ(c.link.port, 1502);
  EXPECT_DOUBLE_EQ(c.travel.max_mm, 350.0);
  EXPECT_THROW(fhpp_axis_config(device("axis", "nowhere"), 350.0), std::runtime_error);
}

TEST(DriverConfigs, CanNodesListEveryIdADeviceOccupiesAndNoneOffTheBus) {
  DeviceConfig head = device("pan_tilt", "can0");
  head.pan_node = 7;
  const auto nodes = can_nodes(head);
  ASSERT_EQ(nodes.size(), 3u);
  EXPECT_EQ(std::string(nodes[1].field), "pan_node");
  EXPECT_EQ(nodes[1].node, 7);
  EXPECT_FALSE(nodes[1].is_default);
  EXPECT_TRUE(nodes[2].is_default);
  EXPECT_TRUE(can_nodes(device("axis", "10.0.0.5:502")).empty());
  EXPECT_TRUE(can_nodes(device("css", "usb")).empty());
  EXPECT_TRUE(can_nodes(DeviceConfig{}).empty());
}

}  // namespace driver_configs_test
}  // namespace rangefit::daemon
