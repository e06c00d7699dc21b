// Numeric command-line options of `rangefit bore`, `rangefit object` and `rangefit request` are
// checked before any work: NaN, infinities and absurd magnitudes are bad input (exit 1) with a
// message naming the option, not a detector run on garbage or a length_error from deep inside it.
#include <gtest/gtest.h>

#include <string>

#include "test/daemon/cli_run.hpp"

namespace cli_options_test {

#ifdef RANGEFIT_CLI_PATH
using rangefit::test::CliRun;
using rangefit::test::run_cli;

// Any existing file passes --cloud's existence check; the options are refused before it is read.
const std::string kCloud = std::string(" --cloud ") + RANGEFIT_SOURCE_DIR + "/data/models/box.toml";
const std::string kBore = "bore" + kCloud + " --cad-entrance 0,0,0 --cad-axis 0,0,1";

TEST(CliOptions, BoreRejectsNonFiniteAndAbsurdNumbers) {
  const std::pair<std::string, std::string> cases[] = {
      {" --cad-radius 5 --normal-keep nan", "--normal-keep: value nan is not a finite number"},
      {" --cad-radius 5 --normal-keep inf", "--normal-keep"},
      {" --cad-radius nan", "--cad-radius: value nan is not a finite number"},
      {" --cad-radius 1e300", "--cad-radius: value 1e300 is not a finite number"},
      {" --cad-radius 5 --sensor-position 1e308,0,0",
       "--sensor-position needs three finite numbers X,Y,Z within +-1e6"},
      {" --cad-radius 5 --view-dir 0,0,1e300", "--view-dir needs three finite numbers"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = run_cli(kBore + args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
  const CliRun entrance = run_cli("bore" + kCloud +
                                  " --cad-entrance 1e308,0,0 --cad-axis 0,0,1 "
                                  "--cad-radius 5");
  EXPECT_NE(entrance.output.find("--cad-entrance and --cad-axis need three finite numbers"),
            std::string::npos)
      << entrance.output;
}

TEST(CliOptions, ObjectRejectsANonFiniteOrAbsurdViewpoint) {
  const std::string object =
      "object" + kCloud + " --model " + RANGEFIT_SOURCE_DIR + "/data/models/box.toml --viewpoint ";
  for (const std::string v : {"nan 0 0", "0 inf 0", "0 0 1e308"}) {
    const CliRun r = run_cli(object + v);
    EXPECT_EQ(r.exit_code, 1) << v << "\n" << r.output;
    EXPECT_NE(r.output.find("--viewpoint: value"), std::string::npos) << v << "\n" << r.output;
  }
}
// `rangefit request calibrate css` needs the sphere and the robot pose, both finite; they are
// checked before the daemon is looked for.
TEST(CliOptions, RequestCalibrateCssNeedsAFiniteSphereAndRobotPose) {
  const std::string css = "request calibrate css --timeout 0.001";
  const std::string pose = " --robot-pose 450,-120,610,0,1.5,0";
  const std::pair<std::string, std::string> cases[] = {
      {pose, "--sphere-radius is required"},
      {" --sphere-radius 12.7", "--robot-pose is required"},
      {" --sphere-radius nan" + pose, "--sphere-radius: value nan is not a finite number"},
      {" --sphere-radius 12.7 --robot-pose 450,-120,inf,0,1.5,0", "--robot-pose: value inf"},
      {" --sphere-radius 12.7 --robot-pose 450,-120,610", "--robot-pose"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = run_cli(css + args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
}
// `rangefit request calibrate pantilt` needs the cube's pose in the head's world; a tilt, when
// given, is finite and within +-pi/2. Both are checked before the daemon is looked for.
TEST(CliOptions, RequestCalibratePantiltNeedsTheCubePoseAndAFiniteTilt) {
  const std::string pantilt = "request calibrate pantilt --timeout 0.001";
  const std::string pose = " --cube-pose 900,-40,250,0,0,0.6";
  const std::pair<std::string, std::string> cases[] = {
      {" --tilt 0.1", "--cube-pose is required"},
      {" --tilt 0.1 --scans sweep-1", "--cube-pose is required"},
      {pose + " --tilt nan", "--tilt: value nan is not a finite number"},
      {pose + " --tilt 2", "--tilt: value 2 is not a finite number"},
      {" --cube-pose 900,-40,inf,0,0,0.6", "--cube-pose: value inf"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = run_cli(pantilt + args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
}
TEST(CliOptions, WatchRejectsANonFiniteDuration) {
  // Before, seconds * 1000 went through an undefined double-to-long conversion.
  for (const std::string v : {"nan", "1e300", "-1"}) {
    const CliRun r = run_cli("watch --seconds " + v);
    EXPECT_EQ(r.exit_code, 1) << v << "\n" << r.output;
    EXPECT_NE(r.output.find("--seconds: value " + v), std::string::npos) << r.output;
  }
}
#endif

}  // namespace cli_options_test
