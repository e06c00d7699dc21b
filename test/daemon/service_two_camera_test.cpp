// The simulated stripe cell, and the pan-tilt head, with a camera on each side of the laser plane
// and a box behind a wall from the first camera: an object request that names both cameras
// (`sensors`) sweeps once and finds the box in their fused clouds, judged with both cameras'
// sight; the first camera alone cannot see it. `rangefit object` does the same with the two
// saved sweeps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "daemon/rangefitd/service.hpp"
#include "test/daemon/cli_run.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/daemon/stripe_cell_config.hpp"

namespace rangefit::daemon {
namespace service_two_camera_test {
namespace fs = std::filesystem;

// The box of table 5.2 standing at (60, 0) turned 45 deg, and a wall 300 mm high on its -y side,
// between it and the first camera (300 mm towards -y from the laser plane, level with the apex).
const Eigen::Vector3d kBoxAt(60.0, 0.0, 50.0);

fs::path write_scene(const fs::path& dir) {
  const fs::path scene = dir / "walled_box.toml";
  std::ofstream(scene) << "[[object]]\nname = \"table\"\ntype = \"plane\"\nsize = [500, 500]\n"
                          "position = [0, 0, 0]\n\n"
                          "[[object]]\nname = \"box\"\ntype = \"superquadric\"\n"
                          "a = [25, 25, 50]\neps = [0.1, 0.1]\nposition = [60, 0, 50]\n"
                          "rpy_deg = [0, 0, 45]\n\n"
                          "[[object]]\nname = \"wall\"\ntype = \"superquadric\"\n"
                          "a = [90, 5, 150]\neps = [0.1, 0.1]\nposition = [60, -55, 150]\n";
  return scene;
}

struct Cell {
  fs::path dir;
  std::optional<DaemonConfig> config;
};

// Two stripe devices over the same scene and sweep: the first camera, and a second one mirrored
// across the laser plane (the same ranger pose, the baseline on the other side).
Cell two_camera_cell(const char* name) {
  Cell c;
  c.dir = test::fresh_test_dir(name);
  const fs::path scene = write_scene(c.dir);
  // Both sweep table y from +60 to -80 mm only (the laser plane is at cell y = 200 mm).
  const std::string sweep = "sweep_start = 140\nsweep_end = 280\n";
  const std::string extra =
      "[[devices]]\nname = \"stripe_b\"\nkind = \"stripe\"\nscene = \"" + scene.string() + "\"\n" +
      sweep +
      "[fusion.stripe_cell]\n[[fusion.stripe_cell.cameras]]\nname = \"stripe_b\"\n"
      "ranger_position_cell_mm = [0, 200, 600]\nranger_rpy_cell_rad = [3.141592653589793, 0, 0]\n"
      "baseline_mm = -300\n";
  const fs::path path =
      test::write_stripe_cell_config(c.dir, "table_top_fig5_18.toml", "box.toml", false, extra);
  // The first device scans the walled box too, over the same sweep.
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string fig =
      (fs::path(RANGEFIT_SOURCE_DIR) / "data/scenes/table_top_fig5_18.toml").string();
  text.replace(text.find(fig) - 1, fig.size() + 3, "\"" + scene.string() + "\"\n" + sweep);
  std::ofstream(path) << text;
  ConfigResult r = load_config(path);
  EXPECT_TRUE(r.config) << r.error;
  c.config = std::move(r.config);
  return c;
}

std::optional<DetectionResult> run(Service& service, const ScanRequest& req) {
  EXPECT_TRUE(service.board().reserve(req.id));
  if (const auto refused = service.admit(req)) return refused;
  return service.board().wait_for(req.id, std::chrono::seconds(120));
}

ScanRequest box_request(const std::string& id) {
  ScanRequest req;
  req.id = id;
  req.kind = DetectKind::kObject;
  req.model = "box";
  req.seed = 3;
  return req;
}

// Both cameras found the box where it stands, the first alone did not, and a pair that is not two
// cameras of one laser plane was refused.
void expect_only_both_see_the_box(const DetectionResult& found, const DetectionResult& alone,
                                  const DetectionResult& refused) {
  ASSERT_TRUE(found.found) << found.reason;
  ASSERT_EQ(found.parts.size(), 1u);
  EXPECT_LT((found.parts[0].T_world_part.translation() - kBoxAt).norm(), 3.0)
      << found.parts[0].T_world_part.translation().transpose();
  EXPECT_FALSE(alone.found) << "the first camera alone sees no box behind the wall";
  EXPECT_FALSE(refused.found);
  EXPECT_NE(refused.reason.find("two cameras of one laser plane"), std::string::npos)
      << refused.reason;
}

TEST(ServiceTwoCameras, BothCamerasOfOneLaserPlaneFindWhatOneCannotSee) {
  Cell cell = two_camera_cell("rangefit_service_two_cameras");
  ASSERT_TRUE(cell.config);
  hal::MonotonicClock clock;
  Service service(*cell.config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  ScanRequest both = box_request("both");
  both.sensors = {"stripe", "stripe_b"};
  const auto found = run(service, both);
  const auto alone = run(service, box_request("first-alone"));
  ScanRequest second = box_request("second-alone");
  second.sensor = "stripe_b";
  const auto other = run(service, second);
  ScanRequest three = box_request("three");
  three.sensors = {"stripe", "stripe_b", "stripe"};
  const auto refused = run(service, three);
  loop.reset();
  ASSERT_TRUE(found && alone && other && refused);
  expect_only_both_see_the_box(*found, *alone, *refused);

#ifdef RANGEFIT_CLI_PATH
  // The spooled scans, read back by the CLI: the fused one says it was taken by both cameras, and
  // the two cameras' own sweeps fuse the same way (with_second_camera).
  const std::string model = (cell.dir / "box.toml").string();
  const auto cli = [&](const std::string& clouds) {
    return test::run_cli("object " + clouds + " --model " + model + " --seed 3 --json");
  };
  const auto cloud_of = [](const std::optional<DetectionResult>& r) {
    return " --cloud " + (fs::path(r->spool_entry) / "cloud.ply").string();
  };
  const test::CliRun replayed = cli(cloud_of(found));
  EXPECT_EQ(replayed.exit_code, 0) << replayed.output;
  const test::CliRun fused = cli(cloud_of(alone) + cloud_of(other));
  EXPECT_EQ(fused.exit_code, 0) << fused.output;
  EXPECT_NE(fused.output.find("\"found\": true"), std::string::npos) << fused.output;
  const test::CliRun first = cli(cloud_of(alone));
  EXPECT_NE(first.exit_code, 0) << first.output;
  // The same camera twice is not two cameras: a clear error, nothing detected.
  const test::CliRun twice = cli(cloud_of(alone) + cloud_of(alone));
  EXPECT_EQ(twice.exit_code, 1) << twice.output;
  EXPECT_NE(twice.output.find("not a second camera"), std::string::npos) << twice.output;
#endif
  fs::remove_all(cell.dir);
}

// The same box and wall under a pan-tilt head 700 mm above the box, looking down: its first
// camera is 425 mm towards -y of the laser plane (behind the wall), the second mirrored, a
// pan_tilt device of its own on the same head (`motion`).
TEST(ServiceTwoCameras, BothCamerasOfAPanTiltHeadFindWhatOneCannotSee) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_two_head_cameras");
  const fs::path scene = write_scene(dir);
  std::ofstream(scene, std::ios::app)
      << "\n[sensors.pantilt]\nposition = [60, 0, 700]\nrpy_deg = [180, 0, 0]\n";
  const std::string devices =
      "[[devices]]\nname = \"head\"\nkind = \"pan_tilt\"\nscene = \"" + scene.string() +
      "\"\n[[devices]]\nname = \"head_b\"\nkind = \"pan_tilt\"\nmotion = \"head\"\nscene = \"" +
      scene.string() + "\"\n[[fusion.pan_tilt.cameras]]\nname = \"head_b\"\nbaseline_mm = -425\n";
  const fs::path path =
      test::write_stripe_cell_config(dir, "table_top_fig5_18.toml", "box.toml", false, devices);
  ConfigResult config = load_config(path);
  ASSERT_TRUE(config.config) << config.error;
  hal::MonotonicClock clock;
  Service service(*config.config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  ScanRequest both = box_request("head-both");
  both.sensors = {"head", "head_b"};
  const auto found = run(service, both);
  ScanRequest first = box_request("head-alone");
  first.sensor = "head";
  const auto alone = run(service, first);
  ScanRequest mixed = box_request("mixed");
  mixed.sensors = {"stripe", "head_b"};
  const auto refused = run(service, mixed);
  loop.reset();
  ASSERT_TRUE(found && alone && refused);
  expect_only_both_see_the_box(*found, *alone, *refused);
  fs::remove_all(dir);
}

}  // namespace service_two_camera_test
}  // namespace rangefit::daemon
