// The service on the simulated cell finds a bore the CLI can find, with what the sensor and the
// request contribute: the 45 deg slanted and the chamfered bore of the bore plate under the CSS,
// through DDS, with the plate's normal in the request and the view direction from the CSS pose.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "daemon/dds/client.hpp"
#include "daemon/rangefitd/service.hpp"
#include "sim/scene_loader.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace sim_bore_service_test {
namespace fs = std::filesystem;

// bore_plate.toml with the plate shifted so that cell `cell` lies under the CSS.
fs::path plate_with_cell_under_sensor(const fs::path& dir, int cell) {
  std::ifstream in(fs::path(RANGEFIT_SOURCE_DIR) / "data/scenes/bore_plate.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::string from = "position = [120.0, 0.0, 285.8]";
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos);
  s.replace(at, from.size(),
            "position = [" + std::to_string(240.0 - (cell + 0.5) * 80.0) + ", 0.0, 285.8]");
  std::ofstream(dir / "plate.toml") << s;
  return dir / "plate.toml";
}

struct PlateBore {
  int cell;
  const char* name;
};

class SimBoreService : public ::testing::TestWithParam<PlateBore> {};

TEST_P(SimBoreService, BoreUnderTheCssIsFoundThroughDdsWithinFiftyMicrons) {
  const fs::path dir =
      test::fresh_test_dir(std::string("rangefit_sim_bore_service_") + GetParam().name);
  const fs::path scene = plate_with_cell_under_sensor(dir, GetParam().cell);
  sim::BoreTruth truth;
  for (const auto& b : sim::load_scene(scene.string()).bores) {
    if (b.name == GetParam().name) truth = b;
  }
  ASSERT_EQ(truth.name, GetParam().name);
  DaemonConfig config;
  config.dds.domain_id = test::dds_test_domain();
  config.spool.directory = dir / "spool";
  config.sim.time_scale = 0.0;
  config.sim.seed = 3;
  DeviceConfig css;
  css.name = css.kind = "css";
  css.scene = scene;
  config.devices.push_back(css);
  config.service.bore_sensor = "css";
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  DdsClient client(config.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  ScanRequest req;
  req.id = "slanted";
  req.kind = DetectKind::kBore;
  req.bore.position_mm = truth.opening_mm + Eigen::Vector3d(0.3, -0.2, 0.0);  // CAD vs. real
  req.bore.axis = -truth.axis;
  req.bore.radius_mm = 0.5 * truth.diameter_mm;
  req.bore.plane_normal = Eigen::Vector3d::UnitZ();  // the plate's top face
  ASSERT_TRUE(client.send(req, false));
  const auto result = client.wait_result(req.id, std::chrono::seconds(120));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason;
  const Eigen::Isometry3d& T = result->parts.at(0).T_world_part;
  EXPECT_LT((T.translation() - truth.opening_mm).norm(), 0.05);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(T.linear().col(2).dot(truth.axis)))) * 180 / M_PI,
            0.1);
  EXPECT_NEAR(result->bore_radius_mm, 0.5 * truth.diameter_mm, 0.05);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Plate, SimBoreService,
                         ::testing::Values(PlateBore{2, "slanted_12"},
                                           PlateBore{3, "chamfered_16"}),
                         [](const auto& p) { return std::string(p.param.name); });

}  // namespace sim_bore_service_test
}  // namespace rangefit::daemon
