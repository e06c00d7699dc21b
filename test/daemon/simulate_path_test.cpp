// `rangefit simulate` scans through the service's simulated cell: the cloud it writes (float64)
// is the one SimCell's scan loop gives rangefitd for the same scene and seed, point for point,
// and the devices' Status is checked there as on the cell.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "daemon/cell/sim_cell.hpp"
#include "io/cloud_io.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace simulate_path_test {
namespace fs = std::filesystem;

#ifdef RANGEFIT_CLI_PATH
int run_cli(const std::string& args) {
  const int status = std::system((std::string(RANGEFIT_CLI_PATH) + " " + args).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SimulatePath, SimulateWritesTheCloudTheServicesSimulatedCellScans) {
  const fs::path dir = test::fresh_test_dir("rangefit_simulate_path_test");
  const fs::path scene = fs::path(RANGEFIT_SOURCE_DIR) / "data/scenes/bore_plate.toml";
  ASSERT_EQ(
      run_cli("simulate --scene " + scene.string() + " --sensor css --seed 7 --double --out " +
              (dir / "scan.ply").string() + " > /dev/null"),
      0);
  const PointCloud cli = io::read_cloud(dir / "scan.ply");

  CellConfig c;
  c.sim.time_scale = 0.0;
  c.sim.seed = 6;  // the cell's first scan uses seed + 1
  DeviceConfig d;
  d.name = d.kind = "css";
  d.scene = scene;
  c.devices.push_back(d);
  SimCell cell(c);
  std::atomic<bool> cancel{false};
  const ScanOutcome out = cell.scan(c.devices.front(), ScanRequest{}, cancel, [] {});
  ASSERT_TRUE(out.status) << out.status.message;
  ASSERT_EQ(cli.size(), out.cloud.size());
  ASSERT_GT(cli.size(), 10000u);
  for (std::size_t i = 0; i < cli.size(); ++i) {
    ASSERT_EQ(cli.points[i], out.cloud.points[i]) << i;
  }
  fs::remove_all(dir);
}

// --mirrored-camera: the second camera sweeps with the first, and the cloud is both views fused
// as rangefitd fuses them: its sensor says so, so `rangefit object` judges it with both cameras.
TEST(SimulatePath, AMirroredCameraAddsItsViewFromTheSameSweep) {
  const fs::path dir = test::fresh_test_dir("rangefit_simulate_mirrored_test");
  const std::string scene =
      (fs::path(RANGEFIT_SOURCE_DIR) / "data/scenes/table_top_fig5_18.toml").string();
  const auto simulate = [&](const std::string& sensor, const std::string& extra,
                            const fs::path& out) {
    return run_cli("simulate --scene " + scene + " --sensor " + sensor + " --seed 3 --out " +
                   out.string() + extra + " > /dev/null 2> " + (dir / "err.txt").string());
  };
  for (const char* sensor : {"stripe", "pantilt"}) {
    SCOPED_TRACE(sensor);
    ASSERT_EQ(simulate(sensor, "", dir / "a.ply"), 0);
    ASSERT_EQ(simulate(sensor, " --mirrored-camera", dir / "ab.ply"), 0);
    const PointCloud a = io::read_cloud(dir / "a.ply");
    const PointCloud ab = io::read_cloud(dir / "ab.ply");
    EXPECT_GT(ab.size(), a.size() + a.size() / 2) << "the second camera's points are added";
    EXPECT_EQ(a.sensor.second_camera_offset.norm(), 0.0);
    EXPECT_GT(ab.sensor.second_camera_offset.norm(), 0.0) << "the cloud names both cameras";
    // Mirrored across the laser plane: the cameras' offsets from it are opposite.
    EXPECT_NEAR(ab.sensor.plane_normal.dot(ab.sensor.second_camera_offset),
                -ab.sensor.plane_normal.dot(ab.sensor.camera_offset), 1e-6);
  }
  EXPECT_EQ(simulate("css", " --mirrored-camera", dir / "c.ply"), 1);
  EXPECT_FALSE(fs::exists(dir / "c.ply"));
  fs::remove_all(dir);
}

#endif

}  // namespace simulate_path_test
}  // namespace rangefit::daemon
