// daemon/sim_cell: the request's scan plan drives the simulated motion, every scanning kind runs
// through its fusion assembler, and bad plans or cancellation end a scan with a clear error.
#include "daemon/cell/sim_cell.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace rangefit::daemon {
namespace sim_cell_test {

const std::string kScenes = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/";

DaemonConfig cell_config() {
  DaemonConfig c;
  c.sim.time_scale = 0.0;
  c.sim.noise = false;
  for (const auto& [name, scene] : {std::pair<std::string, std::string>{"css", "bore_plate.toml"},
                                    {"stripe", "table_top_fig5_18.toml"},
                                    {"pan_tilt", "table_top_fig5_18.toml"}}) {
    DeviceConfig d;
    d.name = d.kind = name;
    d.scene = std::filesystem::path(kScenes) / scene;  // not +: GCC 12 false -Wrestrict
    c.devices.push_back(d);
  }
  DeviceConfig robot;
  robot.name = robot.kind = "robot";
  c.devices.push_back(robot);
  return c;
}

ScanRequest plan(double start, double end, double speed = 0.0) {
  ScanRequest r;
  r.sweep_start = start;
  r.sweep_end = end;
  r.sweep_speed = speed;
  return r;
}

class SimCellTest : public ::testing::Test {
 protected:
  ScanOutcome scan(const std::string& device, const ScanRequest& r) {
    return cell_.scan(*config_.device(device), r, cancel_, [this] { ++progress_; });
  }
  DaemonConfig config_ = cell_config();
  SimCell cell_{config_};
  std::atomic<bool> cancel_{false};
  int progress_ = 0;
};

TEST_F(SimCellTest, EveryScanningKindDeliversAWorldCloudAndReportsProgress) {
  for (const char* device : {"css", "stripe", "pan_tilt"}) {
    progress_ = 0;
    const ScanOutcome out = scan(device, plan(0, 0));
    ASSERT_TRUE(out.status) << device << ": " << out.status.message;
    EXPECT_GT(out.cloud.size(), 10000u) << device;
    EXPECT_GT(progress_, 10) << device;
  }
}

TEST_F(SimCellTest, SweepRangeOfTheRequestSetsHowMuchIsScanned) {
  const std::size_t full_css = scan("css", plan(0, 0)).cloud.size();  // +-5 deg by default
  const std::size_t half_css = scan("css", plan(-0.0436332, 0.0436332)).cloud.size();
  EXPECT_NEAR(static_cast<double>(half_css) / static_cast<double>(full_css), 0.5, 0.1);
  const std::size_t short_stripe = scan("stripe", plan(150, 200)).cloud.size();
  const std::size_t long_stripe = scan("stripe", plan(100, 250)).cloud.size();
  EXPECT_GT(short_stripe, 0u);
  EXPECT_GT(long_stripe, 2 * short_stripe);
}

TEST_F(SimCellTest, SlowerSweepGivesADenserScan) {
  const std::size_t fast = scan("stripe", plan(150, 180, 6.3)).cloud.size();
  const std::size_t slow = scan("stripe", plan(150, 180, 3.15)).cloud.size();
  EXPECT_NEAR(static_cast<double>(slow) / static_cast<double>(fast), 2.0, 0.2);
}

TEST_F(SimCellTest, BadPlansAreErrorsNamingTheDevice) {
  const ScanOutcome asym = scan("css", plan(-0.1, 0.05));
  EXPECT_FALSE(asym.status);
  EXPECT_NE(asym.status.message.find("css: sweep must be symmetric"), std::string::npos);
  const ScanOutcome beyond = scan("stripe", plan(0, 900));
  EXPECT_FALSE(beyond.status);
  EXPECT_NE(beyond.status.message.find("travel"), std::string::npos) << beyond.status.message;
  const ScanOutcome robot = scan("robot", plan(0, 0));
  EXPECT_FALSE(robot.status);
  EXPECT_NE(robot.status.message.find("cannot scan"), std::string::npos);
  EXPECT_TRUE(scan("css", plan(0, 0)).status) << "the cell goes on after refused plans";
}

TEST_F(SimCellTest, CancelledScanEndsWithAnErrorAndNoCloud) {
  cancel_ = true;
  const ScanOutcome out = scan("stripe", plan(0, 0));
  EXPECT_FALSE(out.status);
  EXPECT_NE(out.status.message.find("cancelled"), std::string::npos);
  EXPECT_TRUE(out.cloud.empty());
}

TEST(SimCell, WithoutSimulatedDevicesThereIsNothingToReport) {
  DaemonConfig empty;
  SimCell cell(empty);
  EXPECT_TRUE(cell.health().empty());
}

}  // namespace sim_cell_test
}  // namespace rangefit::daemon
