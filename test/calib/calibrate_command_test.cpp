// `rangefit calibrate`: what an operator runs, on files as the cell would record them.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "calib/calibration_cube.hpp"
#include "calib/raw_sweep_text.hpp"
#include "calib_fixtures.hpp"
#include "fusion/config.hpp"
#include "sim/calibration_scans.hpp"

#ifdef RANGEFIT_CLI_PATH
namespace rangefit::test {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("rangefit_calib_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(const std::string& args, const fs::path& log) {
  const std::string cmd =
      std::string(RANGEFIT_CLI_PATH) + " " + args + " > " + log.string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(CalibrateCommand, StripeWritesAnIncludableFragmentBesideTheConfigAndAReport) {
  const fs::path dir = temp_dir("stripe");
  const hal::StripeCellGeometry nominal;
  const hal::StripeCellGeometry truth = perturbed_cell(nominal, 5);
  calib::RawSweep sweep;
  for (double a = 60.0; a <= 340.0; a += 2.0) sweep.axis_mm.push_back(a);
  const calib::CalibrationCube cube;
  sweep.profiles = sim::simulate_stripe_sweep(
      sim::calibration_cube_scene(cube.edge_mm, cube.bar_mm, cube_on_table(), true), truth,
      sweep.axis_mm, {.sigma_mm = 0.06, .seed = 3});
  std::ofstream(dir / "sweep.txt") << calib::format_raw_sweep(sweep);
  std::ofstream(dir / "rangefitd.toml") << "[fusion.stripe_cell]\n"
                                        << "ranger_position_cell_mm = [0, 200, 600]\n";
  const Eigen::Isometry3d T = cube_on_table();
  const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);
  std::ostringstream pose;
  pose.precision(17);
  pose << T.translation().x() << "," << T.translation().y() << "," << T.translation().z() << ","
       << ypr[2] << "," << ypr[1] << "," << ypr[0];
  const std::string config = (dir / "rangefitd.toml").string();
  ASSERT_EQ(run("calibrate stripe --scans " + (dir / "sweep.txt").string() + " --config " + config +
                    " --cube-pose " + pose.str(),
                dir / "log.txt"),
            0)
      << slurp(dir / "log.txt");
  // Beside the configuration, which itself is untouched.
  ASSERT_TRUE(fs::exists(dir / "calibration_stripe.toml")) << slurp(dir / "log.txt");
  EXPECT_TRUE(fs::exists(dir / "calibration_stripe.toml.report.txt"));
  EXPECT_EQ(slurp(config), "[fusion.stripe_cell]\nranger_position_cell_mm = [0, 200, 600]\n");
  EXPECT_NE(slurp(dir / "calibration_stripe.toml.report.txt").find("1 sigma"), std::string::npos);
  // The fragment is a valid [fusion] configuration and holds the true cell.
  const auto parsed = fusion::load_fusion_config(dir / "calibration_stripe.toml");
  ASSERT_TRUE(parsed.config) << parsed.error;
  const hal::StripeCellGeometry& g = parsed.config->stripe_cell.geometry;
  EXPECT_LT((g.ranger_position_cell_mm - truth.ranger_position_cell_mm).norm(), 0.05);
  EXPECT_LT(angle_between(g.T_cell_ranger().linear(), truth.T_cell_ranger().linear()), 0.01 * kDeg);
  fs::remove_all(dir);
}

TEST(CalibrateCommand, BadSweepFileIsBadInputNamingTheLine) {
  const fs::path dir = temp_dir("bad");
  std::ofstream(dir / "sweep.txt") << "rangefit-raw-sweep 1 stripe 512\np 1.0\n3 1.0\n";
  EXPECT_EQ(run("calibrate stripe --scans " + (dir / "sweep.txt").string() +
                    " --cube-pose 0,0,130,0,0,0 --out " + (dir / "o.toml").string(),
                dir / "log.txt"),
            1);
  EXPECT_NE(slurp(dir / "log.txt").find("sweep.txt:3:"), std::string::npos)
      << slurp(dir / "log.txt");
  EXPECT_FALSE(fs::exists(dir / "o.toml"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rangefit::test
#endif
