#include "daemon/service/config.hpp"

#include <gtest/gtest.h>

#include <ostream>

namespace rangefit::daemon {
namespace config_test {

TEST(DaemonConfig, EmptyFileGivesTheDocumentedDefaults) {
  const auto r = parse_config("");
  ASSERT_TRUE(r.config) << r.error;
  EXPECT_EQ(r.config->service.queue_capacity, 4u);
  EXPECT_EQ(r.config->dds.domain_id, 0u);
  EXPECT_EQ(r.config->dds.cloud_depth, 2);
  EXPECT_EQ(r.config->spool.directory, "/var/lib/rangefitd/spool");
  EXPECT_TRUE(r.config->devices.empty());
}

TEST(DaemonConfig, ShippedSampleConfigIsValid) {
  const auto r = load_config(std::string(RANGEFIT_SOURCE_DIR) + "/systemd/rangefitd.toml");
  ASSERT_TRUE(r.config) << r.error;
  ASSERT_NE(r.config->device("css"), nullptr);
  EXPECT_EQ(r.config->device("css")->driver, DriverKind::kSim);
  ASSERT_NE(r.config->object("box"), nullptr);
  EXPECT_DOUBLE_EQ(r.config->object("box")->scale_mm[0], 40.0);
}

struct BadCase {
  const char* toml;
  const char* field_in_error;
};

// Names the ctest case after the field it checks instead of the struct's raw bytes.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.field_in_error; }

class DaemonConfigErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(DaemonConfigErrors, NameTheOffendingField) {
  const auto r = parse_config(GetParam().toml, "t.toml");
  EXPECT_FALSE(r.config);
  EXPECT_NE(r.error.find(GetParam().field_in_error), std::string::npos) << r.error;
  EXPECT_EQ(r.error.rfind("t.toml", 0), 0u) << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Fields, DaemonConfigErrors,
    ::testing::Values(
        BadCase{"[service]\nqueue_capacity = 0\n", "service.queue_capacity"},
        BadCase{"[service]\nqueu_capacity = 3\n", "service.queu_capacity: unknown field"},
        BadCase{"[service]\nlog_level = \"loud\"\n", "service.log_level"},
        BadCase{"[dds]\ndomain_id = 300\n", "dds.domain_id"},
        BadCase{"[dds]\ndiagnostics_period_s = \"1\"\n",
                "dds.diagnostics_period_s: must be a number"},
        BadCase{"[spool]\ndirectory = \"\"\n", "spool.directory"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\ndriver = \"magic\"\n",
                "devices[0].driver"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"laser\"\n", "devices[0].kind"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\nsweep_end = 30.0\n",
                "t.toml:4: devices[0].sweep_end: must be in [-6.28319, 6.28319], got 30"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\nsweep_start = -1e15\n",
                "devices[0].sweep_start: must be in"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"stripe\"\nsweep_end = 1e7\n",
                "devices[0].sweep_end: must be in [-10000, 10000]"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\ndriver = \"real\"\n",
                "devices[0].transport"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\ndriver = \"replay\"\n",
                "devices[0].replay_file"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\nxyz_mm = [1, 2]\n",
                "devices[0].xyz_mm"},
        BadCase{"[sim]\nscene = \"s.toml\"\n[[devices]]\nname = \"a\"\nkind = \"css\"\n"
                "[[devices]]\nname = \"a\"\nkind = \"css\"\n",
                "devices[1].name: duplicate"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\n", "devices[0].scene: is required"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\nscene = \"s.toml\"\n"
                "[devices.sim_fault]\ndisconnect_for_s = -1\n",
                "devices[0].sim_fault.disconnect_for_s"},
        BadCase{"[sim]\nscene = \"s.toml\"\n[[devices]]\nname = \"b\"\nkind = \"css\"\n"
                "[[fusion.stripe_cell.cameras]]\nname = \"b\"\nranger_position_cell_mm = [0, 0, "
                "0]\nranger_rpy_cell_rad = [0, 0, 0]\nbaseline_mm = 1\n",
                "fusion.stripe_cell.cameras[0].name: no stripe device named \"b\""},
        BadCase{"[sim]\nscene = \"s.toml\"\n[[devices]]\nname = \"b\"\nkind = \"stripe\"\n"
                "[[fusion.pan_tilt.cameras]]\nname = \"b\"\nbaseline_mm = -425\n",
                "fusion.pan_tilt.cameras[0].name: no pan_tilt device named \"b\""},
        BadCase{"[sim]\nscene = \"s.toml\"\n[[devices]]\nname = \"s\"\nkind = \"stripe\"\n"
                "[[devices]]\nname = \"b\"\nkind = \"pan_tilt\"\nmotion = \"s\"\n",
                "devices[1].motion: \"s\" is not a pan_tilt head"},
        BadCase{"[sim]\nscene = \"s.toml\"\n[[devices]]\nname = \"h\"\nkind = \"pan_tilt\"\n"
                "[[devices]]\nname = \"b\"\nkind = \"pan_tilt\"\nmotion = \"h\"\npan_node = 5\n",
                "devices[1].pan_node: a camera on another head has no axes of its own"},
        BadCase{"[sim]\ntime_scale = -1\n", "sim.time_scale"},
        BadCase{"[sim]\nnoise = 1\n", "sim.noise: must be true or false"},
        BadCase{"[fusion.css]\ndeflection_rad = \"x\"\n", "fusion.css.deflection_rad"},
        BadCase{"[fusion.cs]\n", "fusion.cs"},
        BadCase{"[[objects]]\nname = \"b\"\nscale_mm = [1, 1, 1]\nshape = [0.01, 1]\n",
                "objects[0].shape"},
        BadCase{"[[objects]]\nname = \"b\"\n", "objects[0].scale_mm"},
        BadCase{"[[devices]]\nname = \"r\"\nkind = \"robot\"\ncan_node = 128\n",
                "devices[0].can_node: must be in [1, 127]"},
        BadCase{"[[devices]]\nname = \"r\"\nkind = \"robot\"\ncan_node = 0\n",
                "devices[0].can_node: must be in [1, 127]"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"axis\"\nmodbus_unit = 248\n",
                "devices[0].modbus_unit: must be in [1, 247]"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"axis\"\nmodbus_unit = \"7\"\n",
                "devices[0].modbus_unit: must be an integer"},
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"axis\"\ncan_node = 3\n",
                "devices[0].can_node: only for kind pan_tilt, robot or stripe"},
        BadCase{"[[devices]]\nname = \"r\"\nkind = \"robot\"\nmodbus_unit = 3\n",
                "devices[0].modbus_unit: only for kind axis"},
        BadCase{"[[devices]]\nname = \"s\"\nkind = \"stripe\"\npan_node = 3\n",
                "devices[0].pan_node: only for kind pan_tilt"},
        BadCase{"[[devices]]\nname = \"h\"\nkind = \"pan_tilt\"\npan_node = 5\ntilt_node = 5\n",
                "devices[0].tilt_node: CAN node 5 is also this device's pan_node"},
        BadCase{"[service]\nbore_sensor = \"nope\"\n", "service.bore_sensor"},
        BadCase{"[service\n", "t.toml:1"}));

TEST(DaemonConfig, FusionTableIsHandedToFusionsParser) {
  const auto r = parse_config(
      "[fusion.css]\ndeflection_rad = 0.05\njoint = 5\n"
      "[fusion.stripe_cell]\naxis_travel_mm = 300\n");
  ASSERT_TRUE(r.config) << r.error;
  EXPECT_DOUBLE_EQ(r.config->fusion.css.deflection_rad, 0.05);
  EXPECT_EQ(r.config->fusion.css.joint, 5);
  EXPECT_DOUBLE_EQ(r.config->fusion.stripe_cell.geometry.axis_travel_mm, 300.0);
  // Without a [fusion] table, fusion's own (thesis) defaults.
  EXPECT_DOUBLE_EQ(parse_config("").config->fusion.css.geometry.pivot_radius_mm, 285.8);
}

TEST(DaemonConfig, SimDeviceScenesResolveAgainstTheConfigFolder) {
  const auto r = parse_config(
      "[sim]\nscene = \"scenes/plate.toml\"\ntime_scale = 0\n"
      "[[devices]]\nname = \"css\"\nkind = \"css\"\n"
      "[[devices]]\nname = \"stripe\"\nkind = \"stripe\"\nscene = \"/abs/table.toml\"\n"
      "[devices.sim_fault]\ndisconnect_after_s = 5\ndisconnect_for_s = 2\non_scan = 1\n",
      "t.toml", "/etc/rangefitd");
  ASSERT_TRUE(r.config) << r.error;
  EXPECT_EQ(r.config->device("css")->scene, "/etc/rangefitd/scenes/plate.toml");
  EXPECT_EQ(r.config->device("stripe")->scene, "/abs/table.toml");
  EXPECT_DOUBLE_EQ(r.config->device("stripe")->sim_fault.disconnect_after_s, 5.0);
  EXPECT_EQ(r.config->device("stripe")->sim_fault.on_scan, 1);
  EXPECT_LT(r.config->device("css")->sim_fault.disconnect_after_s, 0.0) << "no fault by default";
  EXPECT_DOUBLE_EQ(r.config->sim.time_scale, 0.0);
}

TEST(DaemonConfig, FieldErrorsNameTheLineOfTheField) {
  const auto r = parse_config(
      "[service]\nqueue_capacity = 2\n\n[[devices]]\nname = \"arm\"\nkind = \"robot\"\n"
      "can_node = 300\n",
      "t.toml");
  EXPECT_EQ(r.error.rfind("t.toml:7: devices[0].can_node: must be in [1, 127], got 300", 0), 0u)
      << r.error;
  // A missing field is placed at its table.
  const auto missing = parse_config("[dds]\n[[objects]]\nname = \"b\"\n", "t.toml");
  EXPECT_EQ(missing.error.rfind("t.toml:2: objects[0].scale_mm", 0), 0u) << missing.error;
}

TEST(DaemonConfig, BusAddressesAreReadAndUnsetOnesStayAtTheDriverDefault) {
  const auto r = parse_config(
      "[[devices]]\nname = \"arm\"\nkind = \"robot\"\ndriver = \"real\"\n"
      "transport = \"can0\"\ncan_node = 11\n"
      "[[devices]]\nname = \"head\"\nkind = \"pan_tilt\"\ndriver = \"real\"\n"
      "transport = \"can0\"\ncan_node = 40\npan_node = 12\ntilt_node = 13\n"
      "[[devices]]\nname = \"axis\"\nkind = \"axis\"\ndriver = \"real\"\n"
      "transport = \"10.0.0.5:502\"\nmodbus_unit = 247\n"
      "[[devices]]\nname = \"stripe\"\nkind = \"stripe\"\ndriver = \"real\"\n"
      "transport = \"can1\"\n");
  ASSERT_TRUE(r.config) << r.error;
  EXPECT_EQ(r.config->device("arm")->can_node, 11);
  EXPECT_EQ(r.config->device("head")->can_node, 40);
  EXPECT_EQ(r.config->device("head")->pan_node, 12);
  EXPECT_EQ(r.config->device("head")->tilt_node, 13);
  EXPECT_EQ(r.config->device("axis")->modbus_unit, 247);
  EXPECT_EQ(r.config->device("stripe")->can_node, 0) << "0: the driver's default";
}

// A real robot whose joint sits on can0 at the default node 1 (lines 1-5).
constexpr const char* kArmOnCan0 =
    "[[devices]]\nname = \"arm\"\nkind = \"robot\"\ndriver = \"real\"\ntransport = \"can0\"\n";

TEST(DaemonConfig, RealDevicesSharingANodeOnOneInterfaceIsAnErrorNamingBoth) {
  const std::string arm = kArmOnCan0;
  // The robot's joint and the head's pan axis both default to node 1.
  const auto r = parse_config(arm +
                                  "[[devices]]\nname = \"head\"\nkind = \"pan_tilt\"\n"
                                  "driver = \"real\"\ntransport = \"can0\"\n",
                              "t.toml");
  EXPECT_FALSE(r.config);
  EXPECT_NE(r.error.find("devices[1].pan_node: CAN node 1 (the default) on can0 is also used by "
                         "device \"arm\" (devices[0].can_node)"),
            std::string::npos)
      << r.error;
  // Set explicitly: the error names the field as configured.
  const auto set = parse_config(arm +
                                    "[[devices]]\nname = \"s\"\nkind = \"stripe\"\n"
                                    "driver = \"real\"\ntransport = \"can0\"\ncan_node = 1\n",
                                "t.toml");
  EXPECT_NE(set.error.find("t.toml:11: devices[1].can_node: CAN node 1 on can0 is also used by "
                           "device \"arm\""),
            std::string::npos)
      << set.error;
}

// A further camera on a real head has only its ranger: the head's axes are not claimed twice,
// but its ranger must not share the head's ranger node.
TEST(DaemonConfig, ACameraOnARealHeadClaimsOnlyItsRangersNode) {
  const std::string head =
      "[[devices]]\nname = \"head\"\nkind = \"pan_tilt\"\ndriver = \"real\"\n"
      "transport = \"can0\"\n[[devices]]\nname = \"head_b\"\nkind = \"pan_tilt\"\n"
      "driver = \"real\"\ntransport = \"can0\"\nmotion = \"head\"\n";
  const auto r = parse_config(head + "can_node = 33\n");
  EXPECT_TRUE(r.config) << r.error;
  const auto clash = parse_config(head, "t.toml");
  EXPECT_NE(clash.error.find("devices[1].can_node: CAN node 32 (the default) on can0 is also used "
                             "by device \"head\""),
            std::string::npos)
      << clash.error;
}

TEST(DaemonConfig, SameNodeOnAnotherInterfaceOrOnASimulatedDeviceIsFine) {
  const std::string arm = kArmOnCan0;
  const auto other_bus = parse_config(arm +
                                      "[[devices]]\nname = \"head\"\nkind = \"pan_tilt\"\n"
                                      "driver = \"real\"\ntransport = \"can1\"\n");
  EXPECT_TRUE(other_bus.config) << other_bus.error;
  const auto simulated = parse_config(arm +
                                      "[[devices]]\nname = \"head\"\nkind = \"pan_tilt\"\n"
                                      "scene = \"s.toml\"\ntransport = \"can0\"\n");
  EXPECT_TRUE(simulated.config) << simulated.error;
}

TEST(DaemonConfig, HostileFilesAreErrorsNotCrashes) {
  // Each used to crash rangefitd at start-up or on SIGHUP: stack overflow in toml++ on a key of
  // 40,000 dotted segments, bad_alloc reading /dev/zero; a directory started it with defaults.
  std::string key = "a";
  for (int i = 1; i < 40000; ++i) key += ".a";
  EXPECT_EQ(parse_config(key + " = 1\n", "t.toml").error,
            "t.toml:1: more than 32 dotted key segments");
  EXPECT_EQ(load_config("/dev/zero").error,
            "/dev/zero: is not a regular file (a device, FIFO or socket)");
  const auto dir = load_config(RANGEFIT_SOURCE_DIR);
  EXPECT_FALSE(dir.config);
  EXPECT_NE(dir.error.find("is a directory"), std::string::npos) << dir.error;
  EXPECT_EQ(parse_config("\xc7\xb6 ", "t.toml").error,
            "t.toml:1: non-ASCII character outside a string or comment");
}

TEST(DaemonConfig, MissingFileIsReportedWithItsPath) {
  const auto r = load_config("/nonexistent/rangefitd.toml");
  EXPECT_FALSE(r.config);
  EXPECT_NE(r.error.find("/nonexistent/rangefitd.toml"), std::string::npos);
}

}  // namespace config_test
}  // namespace rangefit::daemon
