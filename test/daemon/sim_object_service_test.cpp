// The service on the simulated stripe cell finds an object from a model file named in its
// configuration: the tapered cone of thesis fig. 5.18 (data/models/cone.toml), through DDS, with
// the stripe cell's sweep as the detector's visibility model.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "daemon/dds/client.hpp"
#include "daemon/rangefitd/service.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/daemon/stripe_cell_config.hpp"

namespace rangefit::daemon {
namespace sim_object_service_test {
namespace fs = std::filesystem;

TEST(SimObjectService, TaperedConeFromItsModelFileIsFoundThroughDds) {
  const fs::path dir = test::fresh_test_dir("rangefit_sim_object_service_test");
  const ConfigResult config =
      load_config(test::write_stripe_cell_config(dir, "table_top_fig5_18.toml", "cone.toml"));
  ASSERT_TRUE(config.config) << config.error;
  hal::MonotonicClock clock;
  Service service(*config.config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  DdsClient client(config.config->dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  ScanRequest req;
  req.id = "cone";
  req.kind = DetectKind::kObject;
  req.model = "cone";
  req.seed = 1;  // the device's whole sweep
  ASSERT_TRUE(client.send(req, true));
  const auto result = client.wait_result(req.id, std::chrono::seconds(120));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason;
  ASSERT_EQ(result->parts.size(), 1u);
  const Eigen::Isometry3d& T = result->parts[0].T_world_part;
  // Thesis 5.2.2: within 3 mm of the truth; a tapered part's axis has a sign (tip at +z).
  EXPECT_LT((T.translation() - Eigen::Vector3d(213.074, 110.438, 40.0)).norm(), 3.0)
      << T.translation().transpose() << " axis " << T.linear().col(2).transpose();
  EXPECT_GT(T.linear().col(2).z(), std::cos(2.0 * M_PI / 180));
  fs::remove_all(dir);
}

}  // namespace sim_object_service_test
}  // namespace rangefit::daemon
