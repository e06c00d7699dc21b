// The service does what the CLI does, through DDS: a replayed scan file gives the same poses as
// `rangefit bore` on that file, requests carry plane normal, instances, counts and seed, every
// instance comes back, and result stamps are the scan's acquisition time.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "daemon/cell/sim_cell.hpp"
#include "daemon/dds/client.hpp"
#include "daemon/dds/messages.hpp"
#include "daemon/rangefitd/service.hpp"
#include "daemon/service/spool.hpp"
#include "io/ply.hpp"
#include "sim/sim_clock.hpp"
#include "sim/superquadric_raycast.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace service_detection_test {
namespace fs = std::filesystem;
using std::chrono::seconds;

const fs::path kExample = fs::path(RANGEFIT_SOURCE_DIR) / "data/examples/bore_plate_r5.ply";

// The CAD prior of data/examples/README.md: entrance and axis 0.4 mm and 2 deg off the truth.
ScanRequest example_bore_request(const std::string& id) {
  ScanRequest req;
  req.id = id;
  req.kind = DetectKind::kBore;
  req.bore.position_mm = {120.3, -40.2, 300.1};
  req.bore.axis = {0.5, -0.32, 0.81};
  req.bore.radius_mm = 5.0;
  req.bore.plane_normal = Eigen::Vector3d(0, -0.342, 0.94);  // the plate is slanted
  req.seed = 4;
  return req;
}

#ifdef RANGEFIT_CLI_PATH
nlohmann::json run_cli_json(const std::string& args, const fs::path& out) {
  const std::string cmd = std::string(RANGEFIT_CLI_PATH) + " " + args + " > " + out.string();
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status)) << cmd;
  std::ifstream in(out);
  return nlohmann::json::parse(in);
}

TEST(ServiceDetection, ReplayedExampleBoreIsFoundWithTheCliPosesBitForBit) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_example_bore_test");
  const DaemonConfig config = test::replay_css_config(dir, kExample);
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  DdsClient client(config.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(seconds(20)));
  const ScanRequest req = example_bore_request("example-bore");
  ASSERT_TRUE(client.send(req, false));
  const auto result = client.wait_result(req.id, seconds(60));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason;
  const Eigen::Vector3d truth(120, -40, 300), axis(0.5, -0.2962, 0.8138);
  const Eigen::Isometry3d& T = result->parts.at(0).T_world_part;
  EXPECT_LT((T.translation() - truth).norm(), 0.1);
  EXPECT_GT(T.linear().col(2).dot(axis.normalized()), std::cos(0.5 * M_PI / 180));
  EXPECT_NEAR(result->bore_radius_mm, 5.0, 0.05);

  const nlohmann::json cli =
      run_cli_json("bore --cloud " + kExample.string() +
                       " --cad-entrance 120.3,-40.2,300.1 --cad-axis 0.5,-0.32,0.81 --cad-radius 5"
                       " --cad-plane-normal 0,-0.342,0.94 --seed 4 --json",
                   dir / "cli.json");
  ASSERT_TRUE(cli.at("found").get<bool>());
  // The spooled result keeps the service's numbers in mm as they left the detector.
  std::string why;
  const auto entry = read_spool_entry(result->spool_entry, &why);
  ASSERT_TRUE(entry) << why;
  const Eigen::Vector3d t = entry->result.parts.at(0).T_world_part.translation();
  for (int k = 0; k < 3; ++k) EXPECT_EQ(t[k], cli.at("entrance")[k].get<double>()) << k;
  EXPECT_EQ(entry->result.bore_radius_mm, cli.at("radius").get<double>());
  const Eigen::Vector3d z = entry->result.parts.at(0).T_world_part.linear().col(2);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(z[k], cli.at("axis")[k].get<double>(), 1e-12) << k;
  fs::remove_all(dir);
}
#endif

TEST(ServiceDetection, ThreeCylinderInstancesComeBackAsThreeDistinctPoses) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_instances_test");
  const Superquadric cylinder{25, 25, 50, 0.1, 1.0, 0, 0};
  std::vector<sim::ScenePart> parts;
  const Eigen::Vector3d centres[3] = {{40, 40, 50}, {200, 60, 50}, {120, 200, 50}};
  for (const auto& c : centres) {
    sim::ScenePart p{"cylinder", cylinder, Eigen::Isometry3d::Identity()};
    p.T_world_part.translation() = c;
    parts.push_back(p);
  }
  sim::SceneView view;
  view.width = 300;
  view.height = 220;
  io::write_ply(dir / "cylinders.ply", sim::render_scene(parts, view).cloud);
  DaemonConfig config = test::replay_css_config(dir, dir / "cylinders.ply");
  config.service.object_sensor = "css";
  config.objects.push_back(inline_object("cylinder", {25, 25, 50}, {0.1, 1.0}));
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  DdsClient client(config.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(seconds(20)));
  ScanRequest req;
  req.id = "three-cylinders";
  req.kind = DetectKind::kObject;
  req.model = "cylinder";
  req.instances = 3;
  req.seed = 2;
  ASSERT_TRUE(client.send(req, false));
  const auto result = client.wait_result(req.id, seconds(60));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason;
  ASSERT_EQ(result->parts.size(), 3u);
  bool matched[3] = {false, false, false};
  for (std::uint32_t i = 0; i < 3; ++i) {
    EXPECT_EQ(result->parts[i].instance, i);
    for (int k = 0; k < 3; ++k) {
      if ((result->parts[i].T_world_part.translation() - centres[k]).norm() < 3.0) {
        matched[k] = true;
      }
    }
  }
  EXPECT_TRUE(matched[0] && matched[1] && matched[2]);
  fs::remove_all(dir);
}

TEST(ServiceDetection, ScanStampIsTheLastSampleOnTheWallClock) {
  DaemonConfig c;
  c.sim.noise = false;
  DeviceConfig d;
  d.name = d.kind = "stripe";
  d.scene = fs::path(RANGEFIT_SOURCE_DIR) / "data/scenes/cluttered_mallet.toml";
  c.devices.push_back(d);
  // Real time, started at CLOCK_MONOTONIC's now: the simulated stamps are monotonic times.
  SimCell cell(c, std::make_unique<sim::SimClock>(1.0, hal::monotonic_now()));
  ScanRequest r;
  r.sweep_start = 0.0;
  r.sweep_end = 1.5;  // mm: ~0.25 s of sweep
  r.sweep_speed = 6.3;
  std::atomic<bool> cancel{false};
  const ScanOutcome out = cell.scan(*c.device("stripe"), r, cancel, [] {});
  ASSERT_TRUE(out.status) << out.status.message;
  ASSERT_TRUE(out.cloud.has_stamps());
  const hal::Timestamp last = *std::max_element(out.cloud.stamps.begin(), out.cloud.stamps.end());
  const auto wall_now = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::system_clock::now().time_since_epoch());
  const std::int64_t expected = (wall_now - (hal::monotonic_now() - last)).count();
  EXPECT_NEAR(static_cast<double>(out.acquired_wall_ns), static_cast<double>(expected), 1e6);
  // The published header carries it.
  DetectionResult result;
  result.acquired_wall_ns = out.acquired_wall_ns;
  const DetectionOut msg(result);
  EXPECT_EQ(
      std::int64_t{msg.msg().header.stamp.sec} * 1'000'000'000 + msg.msg().header.stamp.nanosec,
      out.acquired_wall_ns);
  EXPECT_EQ(msg.first_pose().header.stamp.sec, msg.msg().header.stamp.sec);
}

}  // namespace service_detection_test
}  // namespace rangefit::daemon
