// [[objects]] in rangefitd's configuration: model files (relative to the config file) with
// compound links and taper, and inline superquadrics as a shorthand, all validated at load.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "daemon/service/config.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace config_models_test {
namespace fs = std::filesystem;

const fs::path kModels = fs::path(RANGEFIT_SOURCE_DIR) / "data/models";

TEST(ConfigModels, ModelFileRelativeToTheConfigGivesTheCompoundMalletAndTheTaperedCone) {
  const fs::path dir = test::fresh_test_dir("rangefit_config_models_test");
  fs::copy_file(kModels / "mallet.toml", dir / "mallet.toml");
  fs::create_directories(dir / "models");
  fs::copy_file(kModels / "cone.toml", dir / "models/cone.toml");
  std::ofstream(dir / "rangefitd.toml")
      << "[[objects]]\nmodel = \"mallet.toml\"\n"
      << "[[objects]]\nname = \"cone\"\nmodel = \"models/cone.toml\"\n";
  const ConfigResult r = load_config(dir / "rangefitd.toml");
  ASSERT_TRUE(r.config) << r.error;
  const ObjectModelConfig* mallet = r.config->object("mallet");  // named by the file
  ASSERT_NE(mallet, nullptr);
  ASSERT_EQ(mallet->model.parts.size(), 2u);
  ASSERT_EQ(mallet->model.links.size(), 1u);
  EXPECT_DOUBLE_EQ(mallet->model.links[0].distance_mm, 170.0);
  EXPECT_NEAR(mallet->model.links[0].angle_rad, std::numbers::pi / 2, 1e-12);
  const ObjectModelConfig* cone = r.config->object("cone");
  ASSERT_NE(cone, nullptr);
  ASSERT_EQ(cone->model.parts.size(), 1u);
  EXPECT_NE(cone->model.parts[0].shape.kx, 0.0);  // the file's taper reaches the detector
  fs::remove_all(dir);
}

TEST(ConfigModels, InlineSuperquadricTakesATaper) {
  const ConfigResult r = parse_config(
      "[[objects]]\nname = \"cone\"\nscale_mm = [30, 30, 60]\nshape = [0.1, 1]\n"
      "taper = [0.5, 0.5]\n");
  ASSERT_TRUE(r.config) << r.error;
  const auto& part = r.config->object("cone")->model.parts.at(0);
  EXPECT_DOUBLE_EQ(part.shape.a3, 60.0);
  EXPECT_DOUBLE_EQ(part.shape.kx, 0.5);
  EXPECT_DOUBLE_EQ(part.shape.ky, 0.5);
}

TEST(ConfigModels, BadOrMissingModelFilesAndMixedFormsAreErrorsNamingTheField) {
  const ConfigResult missing =
      parse_config("[[objects]]\nmodel = \"/nonexistent/m.toml\"\n", "t.toml");
  EXPECT_FALSE(missing.config);
  EXPECT_EQ(missing.error.rfind("t.toml:2: objects[0].model: ", 0), 0u) << missing.error;
  EXPECT_NE(missing.error.find("/nonexistent/m.toml"), std::string::npos) << missing.error;
  const ConfigResult mixed = parse_config(
      "[[objects]]\nmodel = \"" + (kModels / "mallet.toml").string() + "\"\nscale_mm = [1, 1, 1]\n",
      "t.toml");
  EXPECT_FALSE(mixed.config);
  EXPECT_NE(mixed.error.find("objects[0].scale_mm"), std::string::npos) << mixed.error;
  const ConfigResult taper =
      parse_config("[[objects]]\nname = \"c\"\nscale_mm = [1, 1, 1]\ntaper = [2, 0]\n");
  EXPECT_FALSE(taper.config);
  EXPECT_NE(taper.error.find("objects[0].taper"), std::string::npos) << taper.error;
}

}  // namespace config_models_test
}  // namespace rangefit::daemon
