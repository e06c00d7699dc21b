#include "fusion/config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

namespace rangefit::fusion {
namespace config_test {

using std::chrono::milliseconds;

TEST(FusionConfig, DocumentWithoutAFusionTableGivesTheThesisDefaults) {
  const FusionConfigResult r = parse_fusion_config(std::string_view("[service]\nx = 1\n"));
  ASSERT_TRUE(r.config) << r.error;
  const CssFusionConfig& css = r.config->css;
  EXPECT_DOUBLE_EQ(css.geometry.standoff_mm, 88.5);
  EXPECT_DOUBLE_EQ(css.geometry.pivot_radius_mm, 285.8);
  EXPECT_NEAR(css.geometry.eta_rad, 28.8 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_NEAR(css.deflection_rad, 5.0 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_DOUBLE_EQ(css.scan_speed_mm_s, 2.0);
  EXPECT_EQ(css.omega_source, OmegaSource::kJointStream);
  EXPECT_DOUBLE_EQ(r.config->pan_tilt.geometry.ranger.baseline_mm, 425.0);
  EXPECT_DOUBLE_EQ(r.config->stripe_cell.geometry.max_speed_mm_s, 6.3);
}

TEST(FusionConfig, EmptyDocumentGivesTheDefaults) {
  EXPECT_TRUE(parse_fusion_config(std::string_view("")).config);
}

TEST(FusionConfig, EveryTableOverridesItsFields) {
  const FusionConfigResult r = parse_fusion_config(std::string_view(R"(
[fusion.time]
max_reference_gap_ms = 20
clock_jump_tolerance_ms = 0.5
max_faults = 3
[fusion.css]
omega_source = "stamps"
joint = 5
eta_rad = 0.5
pivot_radius_mm = 300
[fusion.stripe_cell]
ranger_position_cell_mm = [1, 2, 3]
profile_period_ms = 20
[fusion.stripe_cell.ranger]
points_per_profile = 256
[fusion.pan_tilt]
t_w_mm = [0, 0, 1000]
)"));
  ASSERT_TRUE(r.config) << r.error;
  const FusionConfig& c = *r.config;
  EXPECT_EQ(c.css.limits.max_reference_gap, milliseconds(20));
  EXPECT_EQ(c.pan_tilt.limits.clock_jump_tolerance, std::chrono::microseconds(500));
  EXPECT_EQ(c.stripe_cell.limits.max_faults, 3u);
  EXPECT_EQ(c.css.omega_source, OmegaSource::kStartEndStamps);
  EXPECT_EQ(c.css.joint, 5);
  EXPECT_DOUBLE_EQ(c.css.geometry.eta_rad, 0.5);
  EXPECT_DOUBLE_EQ(c.css.geometry.pivot_radius_mm, 300.0);
  EXPECT_EQ(c.stripe_cell.geometry.ranger_position_cell_mm, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(c.stripe_cell.profile_period, milliseconds(20));
  EXPECT_EQ(c.stripe_cell.geometry.ranger.points_per_profile, 256);
  EXPECT_EQ(c.pan_tilt.geometry.t_w_mm, Eigen::Vector3d(0, 0, 1000));
}

// Each bad document and the text its error must contain.
struct BadCase {
  const char* toml;
  const char* expected;
};

class FusionConfigError : public ::testing::TestWithParam<BadCase> {};

TEST_P(FusionConfigError, NamesTheOffendingField) {
  const FusionConfigResult r = parse_fusion_config(std::string_view(GetParam().toml), "cell.toml");
  EXPECT_FALSE(r.config);
  EXPECT_NE(r.error.find(GetParam().expected), std::string::npos) << r.error;
  EXPECT_EQ(r.error.rfind("cell.toml", 0), 0u) << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    BadDocuments, FusionConfigError,
    ::testing::Values(
        BadCase{"[fusion.css]\nstandof_mm = 88\n", "fusion.css.standof_mm: unknown field"},
        BadCase{"[fusion.css]\nstandoff_mm = \"far\"\n",
                "fusion.css.standoff_mm: must be a number"},
        BadCase{"[fusion.css]\nstandoff_mm = -1\n", "fusion.css.standoff_mm: must be in"},
        BadCase{"[fusion.css]\nomega_source = \"gps\"\n", "fusion.css.omega_source"},
        BadCase{"[fusion.css]\nmin_range_mm = 200\n", "fusion.css.max_range_mm: must exceed"},
        BadCase{"[fusion.time]\nmax_faults = 1.5\n", "fusion.time.max_faults: must be an integer"},
        BadCase{"[fusion.stripe_cell]\naxis_direction_cell = [0, 2]\n",
                "fusion.stripe_cell.axis_direction_cell: must be an array of 3"},
        BadCase{"[fusion.stripe_cell]\naxis_direction_cell = [0, 0.5, 0]\n",
                "must be a unit vector"},
        BadCase{"[fusion.pan_tilt.ranger]\nfan_angle = 1\n",
                "fusion.pan_tilt.ranger.fan_angle: unknown field"},
        BadCase{"[fusion]\ncss = 3\n", "fusion.css: must be a table"},
        BadCase{"fusion = 1\n", "fusion: must be a table"}, BadCase{"[fusion.css\n", "cell.toml:1"},
        BadCase{"[[fusion.stripe_cell.cameras]]\nranger_position_cell_mm = [0, 0, 0]\n"
                "ranger_rpy_cell_rad = [0, 0, 0]\nbaseline_mm = 1\n",
                "name: is required"},
        BadCase{"[[fusion.stripe_cell.cameras]]\nname = \"b\"\nranger_position_cell_mm = [0, 0, "
                "0]\nranger_rpy_cell_rad = [0, 0, 0]\nbaseline_mm = 1\nbase = 2\n",
                "base: unknown field"},
        BadCase{"[[fusion.stripe_cell.cameras]]\nname = \"b\"\nranger_position_cell_mm = [0, 0, "
                "0]\nranger_rpy_cell_rad = [0, 0, 0]\nbaseline_mm = 1\n"
                "[[fusion.stripe_cell.cameras]]\nname = \"b\"\nranger_position_cell_mm = [0, 0, "
                "0]\nranger_rpy_cell_rad = [0, 0, 0]\nbaseline_mm = 1\n",
                "\"b\" is given twice"},
        BadCase{"[[fusion.pan_tilt.cameras]]\nname = \"b\"\n", "baseline_mm: is required"},
        BadCase{"[[fusion.pan_tilt.cameras]]\nname = \"b\"\nbaseline_mm = 0\n",
                "fusion.pan_tilt.cameras[0].baseline_mm: a camera in the laser plane sees nothing"},
        BadCase{"[[fusion.pan_tilt.cameras]]\nname = \"b\"\nbaseline_mm = -425\n"
                "[[fusion.pan_tilt.cameras]]\nname = \"b\"\nbaseline_mm = 425\n",
                "\"b\" is given twice"}));

// A further camera of the laser plane: its device sees the cell from its own pose and side; the
// others see the first camera's, and all share the axis.
TEST(FusionConfig, AFurtherCameraOfTheLaserPlaneGivesItsDeviceItsOwnPoseAndSide) {
  const FusionConfigResult r = parse_fusion_config(std::string_view(
      "[fusion.stripe_cell]\naxis_direction_cell = [0, 0.6, 0.8]\n"
      "[[fusion.stripe_cell.cameras]]\nname = \"stripe_b\"\n"
      "ranger_position_cell_mm = [6, 200, 595]\nranger_rpy_cell_rad = [3.1, 0.03, 0]\n"
      "baseline_mm = -300\n"));
  ASSERT_TRUE(r.config) << r.error;
  const StripeCellFusionConfig& c = r.config->stripe_cell;
  const hal::StripeCellGeometry b = stripe_cell_for(c, "stripe_b").geometry;
  EXPECT_EQ(b.ranger_position_cell_mm, Eigen::Vector3d(6, 200, 595));
  EXPECT_EQ(b.ranger_rpy_cell_rad, Eigen::Vector3d(3.1, 0.03, 0));
  EXPECT_EQ(b.ranger.baseline_mm, -300.0);
  EXPECT_EQ(b.axis_direction_cell, Eigen::Vector3d(0, 0.6, 0.8));
  EXPECT_EQ(stripe_camera_of(c, "stripe_b"), "stripe_b");
  const hal::StripeCellGeometry a = stripe_cell_for(c, "stripe").geometry;
  EXPECT_EQ(a.ranger_position_cell_mm, hal::StripeCellGeometry{}.ranger_position_cell_mm);
  EXPECT_EQ(a.ranger.baseline_mm, 300.0);
  EXPECT_EQ(stripe_camera_of(c, "stripe"), "");
}

// A further camera of the pan-tilt head's laser plane: the same laser, head and fan; only the
// side its camera looks from differs.
TEST(FusionConfig, AFurtherCameraOfTheHeadGivesItsDeviceItsOwnSide) {
  const FusionConfigResult r = parse_fusion_config(
      std::string_view("[fusion.pan_tilt]\nt_w_mm = [1, 2, 3]\n"
                       "[[fusion.pan_tilt.cameras]]\nname = \"head_b\"\nbaseline_mm = -400\n"));
  ASSERT_TRUE(r.config) << r.error;
  const PanTiltFusionConfig& c = r.config->pan_tilt;
  const hal::PanTiltGeometry b = pan_tilt_for(c, "head_b").geometry;
  EXPECT_EQ(b.ranger.baseline_mm, -400.0);
  EXPECT_EQ(b.t_w_mm, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(pan_tilt_for(c, "head").geometry.ranger.baseline_mm, 425.0);
}

TEST(FusionConfig, ErrorsNameTheLineAndCrashInputsAreRefused) {
  EXPECT_EQ(
      parse_fusion_config(std::string_view("[fusion.css]\n\nstandof_mm = 88\n"), "c.toml").error,
      "c.toml:3: fusion.css.standof_mm: unknown field");
  std::string key = "fusion";
  for (int i = 1; i < 40000; ++i) key += ".a";
  EXPECT_EQ(parse_fusion_config(std::string_view("[" + key + "]\n"), "c.toml").error,
            "c.toml:1: more than 32 dotted key segments");
  EXPECT_NE(load_fusion_config("/dev/zero").error.find("not a regular file"), std::string::npos);
}

TEST(FusionConfig, MissingFileIsAnErrorNamingIt) {
  const FusionConfigResult r = load_fusion_config("/nonexistent/fusion.toml");
  EXPECT_FALSE(r.config);
  EXPECT_NE(r.error.find("/nonexistent/fusion.toml"), std::string::npos);
}

TEST(FusionConfig, ChangedFileTakesEffectWithoutARebuild) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("rangefit_fusion_config_test_" + std::to_string(::getpid()) + ".toml");
  for (const double r : {285.8, 290.0}) {
    std::ofstream(path) << "[fusion.css]\npivot_radius_mm = " << r << "\n";
    const FusionConfigResult c = load_fusion_config(path);
    ASSERT_TRUE(c.config) << c.error;
    EXPECT_DOUBLE_EQ(c.config->css.geometry.pivot_radius_mm, r);
  }
  std::filesystem::remove(path);
}

}  // namespace config_test
}  // namespace rangefit::fusion
