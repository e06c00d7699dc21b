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
        BadCase{"[[devices]]\nname = \"a\"\nkind = \"css\"\n[[devices]]\nname = \"a\"\nkind = "
                "\"css\"\n",
                "devices[1].name: duplicate"},
        BadCase{"[[objects]]\nname = \"b\"\nscale_mm = [1, 1, 1]\nshape = [0.01, 1]\n",
                "objects[0].shape"},
        BadCase{"[[objects]]\nname = \"b\"\n", "objects[0].scale_mm"},
        BadCase{"[service]\nbore_sensor = \"nope\"\n", "service.bore_sensor"},
        BadCase{"[service\n", "t.toml:1"}));

TEST(DaemonConfig, MissingFileIsReportedWithItsPath) {
  const auto r = load_config("/nonexistent/rangefitd.toml");
  EXPECT_FALSE(r.config);
  EXPECT_NE(r.error.find("/nonexistent/rangefitd.toml"), std::string::npos);
}

}  // namespace
}  // namespace rangefit::daemon
