// A cylinder's standard errors from its refinement (axis, offset, radius) reach the user the same
// way from `rangefit bore --json` and from the service's result details, with units in the names;
// a cone keeps its own errors in its shape.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "daemon/service/model_detector.hpp"
#include "io/cloud_io.hpp"
#include "test/daemon/cli_run.hpp"

namespace rangefit::daemon {
namespace bore_fit_output_test {
namespace fs = std::filesystem;

const fs::path kExample = fs::path(RANGEFIT_SOURCE_DIR) / "data/examples/bore_plate_r5.ply";

// The CAD prior of data/examples/README.md: entrance and axis 0.4 mm and 2 deg off the truth.
ScanRequest example_request() {
  ScanRequest req;
  req.id = "sigma";
  req.kind = DetectKind::kBore;
  req.bore.position_mm = {120.3, -40.2, 300.1};
  req.bore.axis = {0.5, -0.32, 0.81};
  req.bore.radius_mm = 5.0;
  req.bore.plane_normal = Eigen::Vector3d(0, -0.342, 0.94);
  req.seed = 4;
  return req;
}

// Plausible one-sigma errors of a Ø10 bore's full wall at 0.06 mm noise: above zero, far below
// the ±0.1 mm / 0.2 deg the detector is held to.
void expect_plausible_sigma(const nlohmann::json& sigma) {
  ASSERT_TRUE(sigma.is_object()) << sigma.dump();
  EXPECT_GT(sigma.at("axis_rad").get<double>(), 0.0);
  EXPECT_LT(sigma.at("axis_rad").get<double>(), 0.2 * M_PI / 180);
  EXPECT_GT(sigma.at("offset_mm").get<double>(), 0.0);
  EXPECT_LT(sigma.at("offset_mm").get<double>(), 0.05);
  EXPECT_GT(sigma.at("radius_mm").get<double>(), 0.0);
  EXPECT_LT(sigma.at("radius_mm").get<double>(), 0.05);
}

TEST(BoreFitOutput, ServiceDetailsCarryTheCylindersStandardErrors) {
  const PointCloud cloud = io::read_cloud(kExample);
  ModelDetector detector{DetectorConfig{}};
  const DetectionResult r = detector.detect(cloud, example_request(), ScanSensor{}, {});
  ASSERT_TRUE(r.found) << r.reason;
  ASSERT_TRUE(r.details.contains("sigma")) << r.details.dump();
  expect_plausible_sigma(r.details.at("sigma"));
  EXPECT_EQ(r.details.at("refined"), true);
  EXPECT_EQ(r.details.at("walls"), "inner");
}

#ifdef RANGEFIT_CLI_PATH
TEST(BoreFitOutput, CliJsonReportsTheSameFitFieldsAsTheService) {
  const test::CliRun cli = test::run_command(
      std::string(RANGEFIT_CLI_PATH) + " bore --cloud " + kExample.string() +
      " --cad-entrance 120.3,-40.2,300.1 --cad-axis 0.5,-0.32,0.81 --cad-radius 5"
      " --cad-plane-normal 0,-0.342,0.94 --seed 4 --json");
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  const nlohmann::json j = nlohmann::json::parse(cli.output);
  ASSERT_TRUE(j.contains("sigma")) << j.dump();
  expect_plausible_sigma(j.at("sigma"));
  // Same scan, prior and seed: the service's details hold the same fit fields, bit for bit.
  ModelDetector detector{DetectorConfig{}};
  const DetectionResult r =
      detector.detect(io::read_cloud(kExample), example_request(), ScanSensor{}, {});
  ASSERT_TRUE(r.found) << r.reason;
  for (const char* key : {"sigma", "plane_normal", "refined", "second_fit"}) {
    EXPECT_EQ(j.at(key), r.details.at(key)) << key;
  }
}
#endif

}  // namespace bore_fit_output_test
}  // namespace rangefit::daemon
