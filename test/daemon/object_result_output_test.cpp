// An object detection's scores, and when the object is not found which check each candidate
// failed and by how much, reach the user the same way from `rangefit object --json` and from the
// service's result details.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "daemon/service/model_detector.hpp"
#include "io/cloud_io.hpp"
#include "io/object_model_file.hpp"
#include "test/daemon/cli_run.hpp"
#include "test/daemon/replay_service.hpp"

#ifdef RANGEFIT_CLI_PATH
namespace rangefit::daemon {
namespace object_result_output_test {
namespace fs = std::filesystem;

const std::string kCli = RANGEFIT_CLI_PATH;
const fs::path kData = fs::path(RANGEFIT_SOURCE_DIR) / "data";

ObjectModelConfig model_config(const std::string& name) {
  ObjectModelConfig c;
  c.name = name;
  c.model_file = kData / "models" / (name + ".toml");
  c.model = io::read_object_model(c.model_file);
  return c;
}

// What the service's details say of a request for `model` in the scan, and what the command
// line prints for the same scan, model and seed.
struct BothWays {
  DetectionResult service;
  nlohmann::json cli;
};

BothWays detect_both_ways(const fs::path& scan, const std::string& model) {
  DetectorConfig config;
  config.objects.push_back(model_config(model));
  ModelDetector detector{config};
  ScanRequest req;
  req.id = model;
  req.kind = DetectKind::kObject;
  req.model = model;
  req.seed = 3;
  BothWays out;
  out.service = detector.detect(io::read_cloud(scan), req, ScanSensor{}, {});
  const test::CliRun cli =
      test::run_command(kCli + " object --cloud " + scan.string() + " --model " +
                        config.objects[0].model_file.string() + " --seed 3 --json");
  EXPECT_EQ(cli.exit_code, out.service.found ? 0 : 2) << cli.output;
  out.cli = nlohmann::json::parse(cli.output, nullptr, false);
  return out;
}

// Same scan, model and seed: the same detection, bit for bit (the times aside).
void expect_same_account(const BothWays& b) {
  ASSERT_FALSE(b.cli.is_discarded());
  EXPECT_EQ(b.cli.at("found"), b.service.found);
  for (const char* key : {"instances", "rejections", "hypotheses_evaluated", "plane"}) {
    EXPECT_EQ(b.cli.at(key), b.service.details.at(key)) << key;
  }
  EXPECT_TRUE(b.service.details.at("time_ms").contains("total"));
}

TEST(ObjectResultOutput, ScoresAndRejectionsAreTheSameFromTheServiceAndTheCli) {
  const fs::path dir = test::fresh_test_dir("rangefit_object_result_output_test");
  const fs::path scan = dir / "scene.ply";
  const test::CliRun sim = test::run_command(
      kCli + " simulate --scene " + (kData / "scenes/table_top_fig5_18.toml").string() +
      " --sensor stripe --double --out " + scan.string() + " 2>&1");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;

  // The cone of fig. 5.18: found, its scores in the details (the sweep's own visibility model:
  // the scan's rangefit sensor line).
  const BothWays cone = detect_both_ways(scan, "cone");
  ASSERT_TRUE(cone.service.found) << cone.service.reason;
  expect_same_account(cone);
  const nlohmann::json& scores = cone.service.details.at("instances")[0]["parts"][0]["scores"];
  EXPECT_GE(scores.at("coverage").get<double>(), 0.6) << scores.dump();
  EXPECT_LE(scores.at("seen_through").get<double>(), 0.05) << scores.dump();
  EXPECT_GT(scores.at("measurable").get<int>(), 10) << scores.dump();
  EXPECT_TRUE(scores.at("size_determined").get<bool>()) << scores.dump();

  // The mallet is not on the table: not found, and each rejected candidate names the check it
  // failed, its value and the limit it missed.
  const BothWays mallet = detect_both_ways(scan, "mallet");
  ASSERT_FALSE(mallet.service.found);
  EXPECT_EQ(mallet.service.reason, "not confirmed");
  expect_same_account(mallet);
  const nlohmann::json& rejections = mallet.service.details.at("rejections");
  ASSERT_FALSE(rejections.empty());
  for (const nlohmann::json& x : rejections) {
    EXPECT_FALSE(x.at("check").get<std::string>().empty()) << x.dump();
    EXPECT_TRUE(std::isfinite(x.at("value").get<double>())) << x.dump();
    EXPECT_NE(x.at("value").get<double>(), x.at("limit").get<double>()) << x.dump();
  }
  fs::remove_all(dir);
}

}  // namespace object_result_output_test
}  // namespace rangefit::daemon
#endif
