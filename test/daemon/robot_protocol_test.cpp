// driver = "real" robots choose their joint protocol: CiA 402 (the default) or PowerCube, and
// the driver gets the module id and joint the config names.
#include <gtest/gtest.h>

#include "daemon/cell/driver_configs.hpp"
#include "daemon/service/config.hpp"

namespace rangefit::daemon {
namespace robot_protocol_test {

ConfigResult robot(const std::string& extra) {
  return parse_config(
      "[[devices]]\nname = \"arm\"\nkind = \"robot\"\ndriver = \"real\"\n"
      "transport = \"can0\"\n" +
          extra,
      "t.toml");
}

TEST(RobotProtocol, PowerCubeRobotPollsTheConfiguredModuleForTheCssJoint) {
  const ConfigResult r = robot("protocol = \"powercube\"\ncan_node = 7\n");
  ASSERT_TRUE(r.config) << r.error;
  const DeviceConfig& d = r.config->devices.at(0);
  EXPECT_EQ(d.protocol, JointProtocol::kPowerCube);
  const auto c = robot_powercube_config(d, r.config->fusion.css.joint);
  ASSERT_EQ(c.modules.size(), 1u);
  EXPECT_EQ(c.modules[0].module, 7);
  EXPECT_EQ(c.modules[0].joint, r.config->fusion.css.joint);
  EXPECT_EQ(c.name, "arm");
}

TEST(RobotProtocol, DefaultIsCia402AndOtherValuesOrKindsAreErrors) {
  const ConfigResult plain = robot("");
  ASSERT_TRUE(plain.config) << plain.error;
  EXPECT_EQ(plain.config->devices.at(0).protocol, JointProtocol::kCia402);
  const ConfigResult cia = robot("protocol = \"cia402\"\n");
  ASSERT_TRUE(cia.config) << cia.error;
  EXPECT_EQ(cia.config->devices.at(0).protocol, JointProtocol::kCia402);

  const ConfigResult bad = robot("protocol = \"ethercat\"\n");
  EXPECT_EQ(bad.error, "t.toml:6: devices[0].protocol: must be cia402 or powercube");
  const ConfigResult module = robot("protocol = \"powercube\"\ncan_node = 40\n");
  EXPECT_NE(module.error.find("devices[0].can_node: a PowerCube module id is 1 .. 31"),
            std::string::npos)
      << module.error;
  const ConfigResult axis = parse_config(
      "[[devices]]\nname = \"ax\"\nkind = \"axis\"\ndriver = \"real\"\n"
      "transport = \"10.0.0.5:502\"\nprotocol = \"powercube\"\n",
      "t.toml");
  EXPECT_NE(axis.error.find("devices[0].protocol: only for kind robot"), std::string::npos)
      << axis.error;
}

}  // namespace robot_protocol_test
}  // namespace rangefit::daemon
