// The command line as a user types it: --version on both programs, rangefitd --help, one vector
// syntax (X,Y,Z; the old X Y Z still works where a command took it), and "-" for stdin/stdout.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/cloud_io.hpp"
#include "test/daemon/cli_run.hpp"
#include "test/daemon/replay_service.hpp"

#if defined(RANGEFIT_CLI_PATH) && defined(RANGEFITD_PATH) && defined(RANGEFIT_PROJECT_VERSION)
namespace rangefit {
namespace cli_edges_test {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using Outcome = test::CliRun;

Outcome run(const std::string& command) { return test::run_command(command); }

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const std::string kCli = RANGEFIT_CLI_PATH;
const std::string kDaemon = RANGEFITD_PATH;
const std::string kPlate = RANGEFIT_SOURCE_DIR "/data/scenes/bore_plate.toml";
// The 12 mm bore of the plate scene, as a CAD prior a little off the truth (0, 0, 285.8).
const std::string kBorePrior = " --cad-entrance 0.3,-0.2,285.8 --cad-axis 0,0,-1 --cad-radius 6";

TEST(CliEdges, BothProgramsPrintTheProjectVersion) {
  const Outcome cli = run(kCli + " --version");
  EXPECT_EQ(cli.exit_code, 0);
  EXPECT_EQ(cli.output, "rangefit " RANGEFIT_PROJECT_VERSION "\n");
  const Outcome service = run(kDaemon + " --version");
  EXPECT_EQ(service.exit_code, 0);
  EXPECT_EQ(service.output, "rangefitd " RANGEFIT_PROJECT_VERSION "\n");
}

TEST(CliEdges, RangefitdHelpExitsZeroAndBadUsageTwo) {
  const Outcome help = run(kDaemon + " --help 2>/dev/null");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.output, StartsWith("usage: rangefitd --config FILE"));
  EXPECT_THAT(help.output, HasSubstr("--version"));
  const Outcome none = run(kDaemon + " 2>&1");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_THAT(none.output, StartsWith("usage: rangefitd"));
  const Outcome bad = run(kDaemon + " --frobnicate 2>&1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.output, HasSubstr("unexpected argument '--frobnicate'"));
}

TEST(CliEdges, VectorsAreXyzWithCommasInEveryOfflineCommand) {
  const fs::path dir = test::fresh_test_dir("rangefit_cli_vectors_test");
  PointCloud cloud;
  for (int i = 0; i < 200; ++i) cloud.points.emplace_back(i % 20, i / 20, 0.5 * (i % 7));
  io::write_cloud(dir / "scene.ply", cloud);
  const std::string object = kCli + " object --cloud " + (dir / "scene.ply").string() +
                             " --model " RANGEFIT_SOURCE_DIR
                             "/data/models/sphere.toml --hypotheses 1 --trials 1 --viewpoint ";
  // Accepted (found or not: 0 or 2), in the new and the old form, negative numbers included.
  for (const char* v : {"-5,0,100", "-5 0 100", "-5.5,1e2,+3"}) {
    EXPECT_NE(run(object + v + " >/dev/null 2>&1").exit_code, 1) << v;
  }
  for (const char* v : {"1,2", "1,2,3,4", "a,b,c"}) {
    EXPECT_EQ(run(object + v + " >/dev/null 2>&1").exit_code, 1) << v;
  }
  for (const char* command : {"bore", "object"}) {
    const Outcome help = run(kCli + " " + command + " --help");
    EXPECT_THAT(help.output, HasSubstr("X,Y,Z")) << command;
    EXPECT_THAT(help.output, ::testing::Not(HasSubstr("x y z"))) << command;
  }
  fs::remove_all(dir);
}

TEST(CliEdges, DashPipesCloudsFromSimulateIntoBoreAndObject) {
  const fs::path dir = test::fresh_test_dir("rangefit_cli_stdio_test");
  const std::string cd = "cd " + dir.string() + " && ";
  const std::string simulate = kCli + " simulate --scene " + kPlate + " --sensor css";

  // --out -: the cloud (binary float PLY) on stdout, the summary on stderr, no truth file.
  const Outcome to_stdout = run(cd + simulate + " --out - 2>summary.txt > scan.ply");
  ASSERT_EQ(to_stdout.exit_code, 0);
  const std::string ply = read_file(dir / "scan.ply");
  EXPECT_THAT(ply, StartsWith("ply\nformat binary_little_endian 1.0\n"));
  EXPECT_THAT(ply, HasSubstr("property float x\n"));
  EXPECT_THAT(read_file(dir / "summary.txt"), HasSubstr("points to stdout"));
  EXPECT_FALSE(fs::exists(dir / "-.truth.json"));
  EXPECT_EQ(io::read_cloud(dir / "scan.ply").size(), 89125u);

  // --cloud -: the same bore from a file, from a redirected file and from a pipe.
  const Outcome from_file = run(cd + kCli + " bore --json --cloud scan.ply" + kBorePrior);
  const Outcome redirected = run(cd + kCli + " bore --json --cloud -" + kBorePrior + " < scan.ply");
  const Outcome piped = run(cd + simulate + " --out - --format pcd --double 2>/dev/null | " + kCli +
                            " bore --json --cloud -" + kBorePrior);
  for (const Outcome* r : {&from_file, &redirected, &piped}) {
    EXPECT_EQ(r->exit_code, 0) << r->output;
    EXPECT_THAT(r->output, HasSubstr("\"found\":true"));
  }
  const auto entrance = [](const std::string& json) {
    return json.substr(json.find("\"entrance\""), 80);
  };
  EXPECT_EQ(entrance(redirected.output), entrance(from_file.output));

  const Outcome object = run(cd + kCli +
                             " object --model " RANGEFIT_SOURCE_DIR
                             "/data/models/sphere.toml --hypotheses 1 --trials 1 "
                             "--cloud - < scan.ply");
  EXPECT_NE(object.exit_code, 1) << object.output;

  // Nothing on stdin: a clear error, exit 1.
  const Outcome empty = run(cd + kCli + " bore --cloud -" + kBorePrior + " < /dev/null 2>&1");
  EXPECT_EQ(empty.exit_code, 1);
  EXPECT_THAT(empty.output, HasSubstr("stdin: empty"));

  // --double where simulate writes a file; the truth file beside it as before.
  ASSERT_EQ(run(cd + simulate + " --double --out exact.ply > /dev/null").exit_code, 0);
  EXPECT_THAT(read_file(dir / "exact.ply"), HasSubstr("property double x\n"));
  EXPECT_TRUE(fs::exists(dir / "exact.ply.truth.json"));
  fs::remove_all(dir);
}

}  // namespace cli_edges_test
}  // namespace rangefit
#endif
