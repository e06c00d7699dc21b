#include "daemon/config.hpp"

#include <gtest/gtest.h>

#include <ostream>

namespace rangefit::daemon {
namespace {

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
        BadCase{"[sim]\ntime_scale = -1\n", "sim.time_scale"},
        BadCase{"[sim]\nnoise = 1\n", "sim.noise: must be true or false"},
        BadCase{"[fusion.css]\ndeflection_rad = \"x\"\n", "fusion.css.deflection_rad"},
        BadCase{"[fusion.cs]\n", "fusion.cs"},
        BadCase{"[[objects]]\nname = \"b\"\nscale_mm = [1, 1, 1]\nshape = [0.01, 1]\n",
                "objects[0].shape"},
        BadCase{"[[objects]]\nname = \"b\"\n", "objects[0].scale_mm"},
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

TEST(DaemonConfig, MissingFileIsReportedWithItsPath) {
  const auto r = load_config("/nonexistent/rangefitd.toml");
  EXPECT_FALSE(r.config);
  EXPECT_NE(r.error.find("/nonexistent/rangefitd.toml"), std::string::npos);
}

}  // namespace
}  // namespace rangefit::daemon
