// `rangefit calibrate`: what an operator runs, on files as the cell would record them.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "calib/calibration_cube.hpp"
#include "calib/css_scan_text.hpp"
#include "calib/raw_sweep_text.hpp"
#include "calib_fixtures.hpp"
#include "css_fixtures.hpp"
#include "fusion/config.hpp"
#include "pan_tilt_fixtures.hpp"
#include "sim/calibration_scans.hpp"

#ifdef RANGEFIT_CLI_PATH
namespace rangefit::test {
namespace calibrate_command_test {

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

std::string pose_arg(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);
  std::ostringstream pose;
  pose.precision(17);
  pose << T.translation().x() << "," << T.translation().y() << "," << T.translation().z() << ","
       << ypr[2] << "," << ypr[1] << "," << ypr[0];
  return pose.str();
}

TEST(CalibrateCommand, CssWritesTheMountFieldsAndAReportWithTheBoreAxisError) {
  const fs::path dir = temp_dir("css");
  const hal::CssGeometry g;
  // The mount's true form is the configurable one (eta about x, pivot along z), off the
  // configured values, so the written fields can hold it.
  CssMountTruth truth;
  truth.mount = calib::nominal_mount(g);
  truth.mount.translation().z() += 6.0;
  truth.mount.linear() =
      Eigen::AngleAxisd(g.eta_rad + 2.0 * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  truth.omega_zero = -1.5 * kDeg;
  std::ofstream(dir / "spheres.txt")
      << calib::format_css_scans(css_sphere_scans(g, truth, 0.0, 4, 7));
  std::ofstream(dir / "rangefitd.toml") << "[fusion.css]\nomega_zero_rad = 0\n";
  const std::string config = (dir / "rangefitd.toml").string();
  ASSERT_EQ(run("calibrate css --scans " + (dir / "spheres.txt").string() + " --config " + config +
                    " --sphere-radius 25",
                dir / "log.txt"),
            0)
      << slurp(dir / "log.txt");
  EXPECT_EQ(slurp(config), "[fusion.css]\nomega_zero_rad = 0\n");
  const std::string report = slurp(dir / "calibration_css.toml.report.txt");
  EXPECT_NE(report.find("bore measured along the sensor axis"), std::string::npos) << report;
  EXPECT_EQ(report.find("WARNING"), std::string::npos) << report;
  const auto parsed = fusion::load_fusion_config(dir / "calibration_css.toml");
  ASSERT_TRUE(parsed.config) << parsed.error;
  const auto& css = parsed.config->css;
  EXPECT_NEAR(css.omega_zero_rad, truth.omega_zero, 0.02 * kDeg);
  EXPECT_NEAR(css.geometry.eta_rad, g.eta_rad + 2.0 * kDeg, 0.02 * kDeg);
  EXPECT_NEAR(css.geometry.pivot_radius_mm, g.pivot_radius_mm + 6.0, 0.05);
  fs::remove_all(dir);
}

TEST(CalibrateCommand, CssWarnsWhenTheMountIsOffTheConfigurableForm) {
  const fs::path dir = temp_dir("css_off");
  const hal::CssGeometry g;
  const CssMountTruth truth = perturbed_mount(g, 2);  // turned about all three axes
  std::ofstream(dir / "spheres.txt")
      << calib::format_css_scans(css_sphere_scans(g, truth, 0.0, 5, 5));
  ASSERT_EQ(run("calibrate css --scans " + (dir / "spheres.txt").string() +
                    " --sphere-radius 25 --out " + (dir / "c.toml").string(),
                dir / "log.txt"),
            0)
      << slurp(dir / "log.txt");
  EXPECT_NE(slurp(dir / "c.toml.report.txt").find("WARNING"), std::string::npos);
  fs::remove_all(dir);
}

TEST(CalibrateCommand, PanTiltWritesTheHeadFieldsFromOneFilePerTilt) {
  const fs::path dir = temp_dir("pantilt");
  const hal::PanTiltGeometry nominal = configured_head();
  const hal::PanTiltGeometry truth = perturbed_head(nominal, 4);
  const PanTiltSweeps sweeps = pan_tilt_sweeps(truth, 0.06, 9, {-6.0, 0.0, 6.0}, 0.25);
  std::string files;
  for (std::size_t k = 0; k < sweeps.angles.size(); ++k) {
    calib::RawSweep raw;
    raw.kind = calib::SweepKind::kPanTilt;
    raw.angles = sweeps.angles[k];
    raw.profiles = sweeps.profiles[k];
    const fs::path f = dir / ("tilt" + std::to_string(k) + ".txt");
    std::ofstream(f) << calib::format_raw_sweep(raw);
    files.append(" ").append(f.string());
  }
  std::ofstream(dir / "rangefitd.toml") << "[fusion.pan_tilt]\nt_s_mm = [0, -50, 60]\n";
  ASSERT_EQ(
      run("calibrate pantilt --scans" + files + " --config " + (dir / "rangefitd.toml").string() +
              " --cube-pose " + pose_arg(cube_before_head()),
          dir / "log.txt"),
      0)
      << slurp(dir / "log.txt");
  EXPECT_TRUE(fs::exists(dir / "calibration_pantilt.toml.report.txt"));
  const auto parsed = fusion::load_fusion_config(dir / "calibration_pantilt.toml");
  ASSERT_TRUE(parsed.config) << parsed.error;
  const hal::PanTiltGeometry& g = parsed.config->pan_tilt.geometry;
  EXPECT_LT((g.t_s_mm - truth.t_s_mm).norm(), 0.1);
  EXPECT_LT((g.t_w_mm - truth.t_w_mm).norm(), 0.1);
  EXPECT_NEAR(g.pan_zero_rad, truth.pan_zero_rad, 0.01 * kDeg);
  EXPECT_NEAR(g.tilt_zero_rad, truth.tilt_zero_rad, 0.01 * kDeg);
  // One tilt is not enough, and says so.
  EXPECT_EQ(run("calibrate pantilt --scans " + (dir / "tilt0.txt").string() + " --cube-pose " +
                    pose_arg(cube_before_head()) + " --out " + (dir / "o.toml").string(),
                dir / "log1.txt"),
            2);
  EXPECT_NE(slurp(dir / "log1.txt").find("two or more tilt"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "o.toml"));
  // A stripe sweep is not a pan-tilt sweep.
  std::ofstream(dir / "stripe.txt") << "rangefit-raw-sweep 1 stripe 4\np 1\n";
  EXPECT_EQ(run("calibrate pantilt --scans " + (dir / "stripe.txt").string() + files +
                    " --cube-pose 0,0,750,0,0,0 --out " + (dir / "o.toml").string(),
                dir / "log2.txt"),
            1);
  fs::remove_all(dir);
}

TEST(CalibrateCommand, BadSphereScanFileIsBadInputNamingTheLine) {
  const fs::path dir = temp_dir("bad_css");
  std::ofstream(dir / "s.txt") << "rangefit-css-sphere-scans 1\n0.1 0.2 90\n";
  EXPECT_EQ(run("calibrate css --scans " + (dir / "s.txt").string() + " --sphere-radius 25 --out " +
                    (dir / "o.toml").string(),
                dir / "log.txt"),
            1);
  EXPECT_NE(slurp(dir / "log.txt").find("s.txt:2:"), std::string::npos) << slurp(dir / "log.txt");
  EXPECT_FALSE(fs::exists(dir / "o.toml"));
  fs::remove_all(dir);
}

// Two cameras of one laser plane, one on each side: a sweep each, in the order the configuration
// lists the cameras; the fragment holds both, and reads back as the true cell.
TEST(CalibrateCommand, StripeCalibratesTheCamerasOfOneLaserPlaneFromASweepEach) {
  const fs::path dir = temp_dir("stripe_rig");
  const hal::StripeCellGeometry nominal;
  const hal::StripeCellGeometry truth_a = perturbed_cell(nominal, 8);
  Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
  P.linear() = Eigen::AngleAxisd(-3.0 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  P.translation() = Eigen::Vector3d(-4.0, 0.0, 7.0);
  const hal::StripeCellGeometry truth_b = other_side_camera(truth_a, P);
  const Eigen::Isometry3d T_cube = cube_between_cameras();
  for (const auto& [name, sweep] :
       {std::pair{"a.txt", stripe_cube_sweep(truth_a, {.sigma_mm = 0.06, .seed = 4}, 2.0, T_cube)},
        std::pair{"b.txt",
                  other_side_sweep(truth_a, P, {.sigma_mm = 0.06, .seed = 5}, 2.0, T_cube)}}) {
    calib::RawSweep raw;
    raw.axis_mm = sweep.axis;
    raw.profiles = sweep.profiles;
    std::ofstream(dir / name) << calib::format_raw_sweep(raw);
  }
  const hal::StripeCellGeometry start_b = other_side_camera(nominal, Eigen::Isometry3d::Identity());
  std::ostringstream config;
  config.precision(17);
  config << "[[fusion.stripe_cell.cameras]]\nname = \"stripe_b\"\n"
         << "ranger_position_cell_mm = [" << start_b.ranger_position_cell_mm.x() << ", "
         << start_b.ranger_position_cell_mm.y() << ", " << start_b.ranger_position_cell_mm.z()
         << "]\nranger_rpy_cell_rad = [" << start_b.ranger_rpy_cell_rad.x() << ", "
         << start_b.ranger_rpy_cell_rad.y() << ", " << start_b.ranger_rpy_cell_rad.z()
         << "]\nbaseline_mm = -300\n";
  std::ofstream(dir / "rangefitd.toml") << config.str();
  const std::string scans =
      " --scans " + (dir / "a.txt").string() + " --scans " + (dir / "b.txt").string();
  const std::string rest =
      " --config " + (dir / "rangefitd.toml").string() + " --cube-pose " + pose_arg(T_cube);
  ASSERT_EQ(run("calibrate stripe" + scans + rest, dir / "log.txt"), 0) << slurp(dir / "log.txt");
  const auto parsed = fusion::load_fusion_config(dir / "calibration_stripe.toml");
  ASSERT_TRUE(parsed.config) << parsed.error << "\n" << slurp(dir / "calibration_stripe.toml");
  const fusion::StripeCellFusionConfig& cell = parsed.config->stripe_cell;
  ASSERT_EQ(cell.cameras.size(), 1u);
  EXPECT_EQ(cell.cameras[0].name, "stripe_b");
  for (const auto& [name, truth] : {std::pair{"", truth_a}, std::pair{"stripe_b", truth_b}}) {
    const hal::StripeCellGeometry g = fusion::stripe_cell_for(cell, name).geometry;
    SCOPED_TRACE(name);
    EXPECT_LT((g.ranger_position_cell_mm - truth.ranger_position_cell_mm).norm(), 0.05);
    EXPECT_LT(angle_between(g.T_cell_ranger().linear(), truth.T_cell_ranger().linear()),
              0.01 * kDeg);
    EXPECT_EQ(g.ranger.baseline_mm, truth.ranger.baseline_mm);
  }
  EXPECT_NE(slurp(dir / "calibration_stripe.toml.report.txt").find("camera 2, \"stripe_b\""),
            std::string::npos)
      << slurp(dir / "calibration_stripe.toml.report.txt");
  // A third sweep has no camera in the configuration to belong to.
  EXPECT_EQ(run("calibrate stripe" + scans + " --scans " + (dir / "a.txt").string() + rest +
                    " --out " + (dir / "o.toml").string(),
                dir / "log3.txt"),
            1);
  EXPECT_NE(slurp(dir / "log3.txt").find("3 sweeps, but the configuration has 2 camera(s)"),
            std::string::npos)
      << slurp(dir / "log3.txt");
  EXPECT_FALSE(fs::exists(dir / "o.toml"));
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

}  // namespace calibrate_command_test
}  // namespace rangefit::test
#endif
