// End to end through DDS with the real detector: rangefitd's service replays a synthetic
// bore-plate scan (test/support/synthetic_bore) as the CSS device and answers a bore request from a
// separate DDS participant; the pose must agree with the ground truth.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "daemon/dds/client.hpp"
#include "daemon/rangefitd/service.hpp"
#include "io/ply.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit::daemon {
namespace bore_replay_test {
namespace fs = std::filesystem;

TEST(BoreReplayThroughDds, BoreRequestFindsTheSimulatedBoreWithinTolerance) {
  const fs::path dir = test::fresh_test_dir("rangefit_bore_replay_test");
  sim::SyntheticBoreOptions opt;
  opt.radius = 5.0;
  opt.seed = 7;
  const auto scan = sim::make_synthetic_bore(opt);
  io::write_ply(dir / "plate.ply", scan.cloud);

  const DaemonConfig config = test::replay_css_config(dir, dir / "plate.ply");
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);

  DdsClient client(config.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  ScanRequest req;
  req.id = "bore-1";
  req.kind = DetectKind::kBore;
  req.bore.position_mm = scan.truth.entrance + Eigen::Vector3d(0.5, -0.3, 0.2);  // CAD vs real
  req.bore.axis = scan.truth.axis;
  req.bore.radius_mm = 5.0;
  ASSERT_TRUE(client.send(req, false));
  const auto result = client.wait_result("bore-1", std::chrono::seconds(60));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason;
  EXPECT_NEAR(result->bore_radius_mm, scan.truth.radius, 0.1);
  const auto& T = result->parts.at(0).T_world_part;
  EXPECT_LT((T.translation() - scan.truth.entrance).norm(), 0.3);
  EXPECT_GT(std::abs(T.linear().col(2).dot(scan.truth.axis)), std::cos(1.0 * M_PI / 180.0));
  EXPECT_EQ(result->num_points, scan.cloud.size());
  fs::remove_all(dir);
}

}  // namespace bore_replay_test
}  // namespace rangefit::daemon
