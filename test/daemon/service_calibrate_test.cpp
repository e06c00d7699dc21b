// Calibrations over several requests, through the service. The CSS mount: the robot program
// moves the robot to a pose and sends a `calibrate` request with target "css", the sphere's
// radius and the pose; the simulated cell scans the precision sphere there (the CSS at 60 um
// noise). The pan-tilt head: the cell program holds a tilt and sends a `calibrate` request with
// target "pantilt", the cube's pose and the tilt; the simulated head sweeps the cube there. Each
// request leaves its pose's samples or its sweep in the spool (css_sphere_scan.txt,
// raw_sweep_pantilt.txt); one that names the earlier ones solves, which must come back to the
// configured geometry (the simulated cell runs on it), and `rangefit calibrate` on the spooled
// files gives the same answer.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "calib/css_calibration.hpp"
#include "calib/css_scan_text.hpp"
#include "daemon/rangefitd/service.hpp"
#include "detect/common/angles.hpp"
#include "fusion/config.hpp"
#include "test/calib/calib_fixtures.hpp"
#include "test/daemon/cli_run.hpp"
#include "test/daemon/cube_scene.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace service_calibrate_test {
namespace fs = std::filesystem;

const Eigen::Vector3d kCentre(400.0, -150.0, 80.0);
constexpr double kRadius = 25.0;

DaemonConfig css_cell(const fs::path& dir) {
  std::ofstream(dir / "sphere.toml") << "[[object]]\nname = \"ball\"\ntype = \"sphere\"\n"
                                     << "radius = " << kRadius << "\nposition = [" << kCentre.x()
                                     << ", " << kCentre.y() << ", " << kCentre.z() << "]\n";
  DaemonConfig config;
  config.dds.domain_id = test::dds_test_domain();
  config.spool.directory = dir / "spool";
  config.spool.pictures = false;
  config.sim.time_scale = 0.0;
  config.sim.seed = 5;
  // The solve over 4 x 63,000 samples takes ~1.5 s here, but ~40 s in the sanitizer build.
  config.detection.timeout_s = 300.0;
  DeviceConfig css;
  css.name = css.kind = "css";
  css.scene = dir / "sphere.toml";
  config.devices.push_back(css);
  config.service.bore_sensor = "css";
  return config;
}

// Robot pose i: the sensor 30 mm above the ball's centre along its own axis, looking at it from
// 15 or 35 deg off vertical, the wrist turned between poses (as the calibration tests' poses).
Eigen::Isometry3d robot_pose(const hal::CssGeometry& g, int i) {
  Eigen::Isometry3d T_base_css = Eigen::Isometry3d::Identity();
  T_base_css.linear() = (Eigen::AngleAxisd(i * 45.0 * kDeg, Eigen::Vector3d::UnitZ()) *
                         Eigen::AngleAxisd((i % 2 ? 35.0 : 15.0) * kDeg, Eigen::Vector3d::UnitX()) *
                         Eigen::AngleAxisd(i * 70.0 * kDeg, Eigen::Vector3d::UnitZ()))
                            .toRotationMatrix();
  T_base_css.translation() = kCentre + T_base_css.linear() * Eigen::Vector3d(0.0, 0.0, 30.0);
  return T_base_css * calib::nominal_mount(g).inverse();
}

ScanRequest css_request(const std::string& id, const Eigen::Isometry3d& pose,
                        std::vector<std::string> earlier) {
  ScanRequest req;
  req.id = id;
  req.kind = DetectKind::kCalibrate;
  req.target.kind = "css";
  req.target.radius_mm = kRadius;
  req.target.T_base_joint = pose;
  req.target.scans = std::move(earlier);
  return req;
}

std::optional<DetectionResult> run(Service& service, const ScanRequest& req) {
  EXPECT_TRUE(service.board().reserve(req.id));
  if (const auto refused = service.admit(req)) return refused;
  return service.board().wait_for(req.id, std::chrono::seconds(120));
}

// The cell with a stripe cell beside it: a sensor of another kind.
DaemonConfig with_stripe(DaemonConfig config, const fs::path& scene) {
  DeviceConfig stripe;
  stripe.name = stripe.kind = "stripe";
  stripe.scene = scene;
  config.devices.push_back(stripe);
  return config;
}

// Why the service refuses the request; "admitted" when it does not.
std::string refusal(Service& service, const ScanRequest& req) {
  const auto r = service.admit(req);
  return r ? r->reason : std::string("admitted");
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ServiceCalibrateCss, FourRobotPosesGiveTheConfiguredMountAndTheCliAgrees) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_calibrate_css");
  const DaemonConfig config = css_cell(dir);
  const hal::CssGeometry& g = config.fusion.css.geometry;
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  std::vector<std::string> ids;
  std::vector<fs::path> files;
  std::optional<DetectionResult> last;
  for (int i = 0; i < 4; ++i) {
    const std::string id = "css-pose-" + std::to_string(i);
    last = run(service, css_request(id, robot_pose(g, i), ids));
    ASSERT_TRUE(last);
    ASSERT_EQ(last->reason.find("error"), std::string::npos) << last->reason;
    EXPECT_FALSE(last->details.at("applied").get<bool>());
    ASSERT_TRUE(last->details.is_object()) << last->reason;
    EXPECT_GT(last->details.at("samples").get<std::size_t>(), 1000u) << last->details.dump();
    files.push_back(last->details.at("files").at("css_sphere_scan.txt").get<std::string>());
    EXPECT_EQ(files.back().parent_path(), fs::path(last->spool_entry));
    if (i < 2) {  // two poses do not determine the mount: recorded, not calibrated
      EXPECT_FALSE(last->found);
      EXPECT_NE(last->reason.find(std::to_string(i + 1) + " of at least 3 robot poses"),
                std::string::npos)
          << last->reason;
    }
    ids.push_back(id);
  }
  loop.reset();
  ASSERT_TRUE(last->found) << last->reason << " " << last->details.dump();
  EXPECT_EQ(last->details.at("poses").get<std::size_t>(), 4u);
  EXPECT_LT(last->details.at("rms_mm").get<double>(), 0.08);  // the CSS's 60 um noise
  const auto& f = last->details.at("fusion.css");
  const double eta = f.at("eta_rad").get<double>();
  const double pivot = f.at("pivot_radius_mm").get<double>();
  const double zero = f.at("omega_zero_rad").get<double>();
  // Four poses leave the sensor axis a reported 1 sigma of 0.027 deg at this noise (eight:
  // 0.019 deg; the calibration's own tests hold 0.02 deg with eight): eta within 2 sigma.
  const double axis_sigma = last->details.at("sigma").at("axis_rad").get<double>();
  EXPECT_LT(axis_sigma, 0.03 * kDeg);
  EXPECT_LT(std::abs(eta - g.eta_rad), 2.0 * axis_sigma) << last->details.dump();
  EXPECT_LT(std::abs(pivot - g.pivot_radius_mm), 0.05);
  EXPECT_LT(std::abs(zero - config.fusion.css.omega_zero_rad), 0.02 * kDeg);
  const auto& c = last->details.at("sphere_centre_mm");
  EXPECT_LT((Eigen::Vector3d(c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>()) -
             kCentre)
                .norm(),
            0.05);
  const fs::path toml = last->details.at("files").at("calibration_css.toml").get<std::string>();
  EXPECT_NE(text_of(toml).find("[fusion.css]"), std::string::npos);
  // Never applied: the running configuration is the one it started with.
  EXPECT_EQ(service.config_copy().fusion.css.geometry.eta_rad, g.eta_rad);

  // The spooled per-pose files are what `rangefit calibrate css --scans` reads: same answer.
  std::string args = "calibrate css --sphere-radius 25 --out " + (dir / "cli.toml").string();
  args += " --scans";
  for (const fs::path& p : files) args += " " + p.string();
  const test::CliRun cli = test::run_cli(args);
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  const auto parsed = fusion::load_fusion_config(dir / "cli.toml");
  ASSERT_TRUE(parsed.config) << parsed.error;
  // The files hold 12 digits per sample: the same answer to far below its uncertainty.
  EXPECT_NEAR(parsed.config->css.geometry.eta_rad, eta, 1e-7);
  EXPECT_NEAR(parsed.config->css.geometry.pivot_radius_mm, pivot, 1e-5);
  EXPECT_NEAR(parsed.config->css.omega_zero_rad, zero, 1e-7);
  fs::remove_all(dir);
}

TEST(ServiceCalibrateCss, AnUnknownEarlierScanIsNamedAndThisPoseIsStillRecorded) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_calibrate_css_unknown");
  const DaemonConfig config = css_cell(dir);
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  const auto r = run(service, css_request("pose-a", robot_pose(config.fusion.css.geometry, 0),
                                          {"pose-before-restart"}));
  loop.reset();
  ASSERT_TRUE(r);
  EXPECT_FALSE(r->found);
  EXPECT_NE(r->reason.find("\"pose-before-restart\""), std::string::npos) << r->reason;
  EXPECT_TRUE(fs::exists(r->details.at("files").at("css_sphere_scan.txt").get<std::string>()));
  fs::remove_all(dir);
}

TEST(ServiceCalibrateCss, ARequestWithoutRobotPoseOrRadiusOrOnAnotherSensorIsRefused) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_calibrate_css_refused");
  const DaemonConfig config = with_stripe(css_cell(dir), dir / "sphere.toml");
  hal::MonotonicClock clock;
  Service service(config, clock);
  const Eigen::Isometry3d pose = robot_pose(config.fusion.css.geometry, 0);
  const auto refused = [&](const ScanRequest& req) { return refusal(service, req); };
  ScanRequest no_pose = css_request("a", pose, {});
  no_pose.target.T_base_joint.reset();
  EXPECT_NE(refused(no_pose).find("needs robot_pose"), std::string::npos) << refused(no_pose);
  ScanRequest no_radius = css_request("b", pose, {});
  no_radius.target.radius_mm = 0.0;
  EXPECT_NE(refused(no_radius).find("radius_mm"), std::string::npos);
  ScanRequest itself = css_request("c", pose, {"c"});
  EXPECT_NE(refused(itself).find("this request itself"), std::string::npos);
  ScanRequest twice = css_request("d", pose, {"x", "x"});
  EXPECT_NE(refused(twice).find("twice"), std::string::npos);
  ScanRequest on_stripe = css_request("e", pose, {});
  on_stripe.sensor = "stripe";
  EXPECT_NE(refused(on_stripe).find("needs a css sensor"), std::string::npos) << refused(on_stripe);
  ScanRequest nan_pose = css_request("f", pose, {});
  nan_pose.target.T_base_joint->translation().x() = std::nan("");
  EXPECT_NE(refused(nan_pose).find("robot_pose must be finite"), std::string::npos);
  fs::remove_all(dir);
}

DaemonConfig head_cell(const fs::path& dir) {
  test::write_cube_scene(dir / "cube.toml", 120.0, 12.0, test::cube_before_head(), false);
  DaemonConfig config;
  config.dds.domain_id = test::dds_test_domain();
  config.spool.directory = dir / "spool";
  config.spool.pictures = false;
  config.sim.time_scale = 0.0;
  config.sim.seed = 6;
  // Without the ranger's quantisation the sweeps are exact and the head comes back to 0.05 mm /
  // 0.01 deg. (With it, measured: the plane rms is 0.2 mm and t_s along the pan axis 0.2 mm off,
  // 3.4 times its reported sigma: the quantisation's errors are not independent.)
  config.sim.noise = false;
  DeviceConfig head;
  head.name = "head";
  head.kind = "pan_tilt";
  head.scene = dir / "cube.toml";
  config.devices.push_back(head);
  config.service.object_sensor = "head";
  return config;
}

// One pan sweep of +-12 deg at 10 deg/s (0.1 deg between profiles) at a held tilt.
ScanRequest pan_tilt_request(const std::string& id, double tilt_deg,
                             std::vector<std::string> earlier) {
  ScanRequest req;
  req.id = id;
  req.kind = DetectKind::kCalibrate;
  req.sensor = "head";
  req.sweep_start = -12.0 * kDeg;
  req.sweep_end = 12.0 * kDeg;
  req.sweep_speed = 10.0 * kDeg;
  req.seed = 3;
  req.target.kind = "pantilt";
  req.target.T_table_target = test::cube_before_head();
  req.target.tilt_rad = tilt_deg * kDeg;
  req.target.scans = std::move(earlier);
  return req;
}

Eigen::Vector3d vec_of(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

TEST(ServiceCalibratePanTilt, ThreeTiltsGiveTheConfiguredHeadAndTheCliAgrees) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_calibrate_pantilt");
  const DaemonConfig config = head_cell(dir);
  const hal::PanTiltGeometry& g = config.fusion.pan_tilt.geometry;
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  std::vector<std::string> ids;
  std::vector<fs::path> files;
  std::optional<DetectionResult> last;
  const double tilts[] = {-6.0, 0.0, 6.0};
  for (const double tilt : tilts) {
    const std::string id = "tilt-" + std::to_string(ids.size());
    last = run(service, pan_tilt_request(id, tilt, ids));
    ASSERT_TRUE(last);
    ASSERT_EQ(last->reason.find("error"), std::string::npos) << last->reason;
    EXPECT_NEAR(last->details.at("tilt_rad").get<double>(), tilt * kDeg, 1e-9);
    files.push_back(last->details.at("files").at("raw_sweep_pantilt.txt").get<std::string>());
    if (ids.empty()) {  // one tilt cannot tell t_s along the pan axis from t_w
      EXPECT_FALSE(last->found);
      EXPECT_NE(last->reason.find("1 of at least 2 tilts"), std::string::npos) << last->reason;
    }
    ids.push_back(id);
  }
  loop.reset();
  ASSERT_TRUE(last->found) << last->reason << " " << last->details.dump();
  EXPECT_EQ(last->details.at("sweeps").get<std::size_t>(), 3u);
  const auto& f = last->details.at("fusion.pan_tilt");
  const Eigen::Vector3d t_s = vec_of(f.at("t_s_mm")), t_w = vec_of(f.at("t_w_mm"));
  EXPECT_LT((t_s - g.t_s_mm).norm(), 0.05) << last->details.dump();
  EXPECT_LT((t_w - g.t_w_mm).norm(), 0.05);
  EXPECT_LT(std::abs(f.at("pan_zero_rad").get<double>() - g.pan_zero_rad), 0.01 * kDeg);
  EXPECT_LT(std::abs(f.at("tilt_zero_rad").get<double>() - g.tilt_zero_rad), 0.01 * kDeg);
  EXPECT_NE(text_of(last->details.at("files").at("calibration_pantilt.toml").get<std::string>())
                .find("[fusion.pan_tilt]"),
            std::string::npos);

  // The spooled sweeps are what `rangefit calibrate pantilt --scans` reads: same answer.
  double pose[6];
  calib::xyz_rpy_of(test::cube_before_head(), pose);
  std::ostringstream args;
  args.precision(17);
  args << "calibrate pantilt --seed 3 --cube 120,12 --cube-pose " << pose[0];
  for (int k = 1; k < 6; ++k) args << "," << pose[k];
  args << " --out " << (dir / "cli.toml").string() << " --scans";
  for (const fs::path& p : files) args << " " << p.string();
  const test::CliRun cli = test::run_cli(args.str());
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  const auto parsed = fusion::load_fusion_config(dir / "cli.toml");
  ASSERT_TRUE(parsed.config) << parsed.error;
  EXPECT_LT((parsed.config->pan_tilt.geometry.t_s_mm - t_s).norm(), 1e-6);
  EXPECT_LT((parsed.config->pan_tilt.geometry.t_w_mm - t_w).norm(), 1e-6);
  fs::remove_all(dir);
}

TEST(ServiceCalibratePanTilt, TheHeadsTargetTakesItsCliSpellingAndAStripeTargetNoTilt) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_calibrate_pantilt_refused");
  const DaemonConfig config = with_stripe(head_cell(dir), dir / "cube.toml");
  hal::MonotonicClock clock;
  Service service(config, clock);
  const auto refused = [&](const ScanRequest& req) { return refusal(service, req); };
  ScanRequest tilt_on_stripe = pan_tilt_request("a", 0.0, {});
  tilt_on_stripe.target.kind = "stripe";
  tilt_on_stripe.sensor = "stripe";
  EXPECT_NE(refused(tilt_on_stripe).find("tilt_rad is for the pantilt target only"),
            std::string::npos);
  // A stripe target joins the other cameras' sweeps, checked as the other targets' scans.
  ScanRequest scans_on_stripe = tilt_on_stripe;
  scans_on_stripe.target.tilt_rad.reset();
  scans_on_stripe.target.scans = {"x", "x"};
  EXPECT_NE(refused(scans_on_stripe).find("scans names a request twice"), std::string::npos)
      << refused(scans_on_stripe);
  ScanRequest steep = pan_tilt_request("b", 100.0, {});
  EXPECT_NE(refused(steep).find("tilt_rad must be within"), std::string::npos);
  ScanRequest on_stripe = pan_tilt_request("c", 0.0, {});
  on_stripe.sensor = "stripe";
  EXPECT_NE(refused(on_stripe).find("needs a pan_tilt sensor"), std::string::npos)
      << refused(on_stripe);
  fs::remove_all(dir);
}

}  // namespace service_calibrate_test
}  // namespace rangefit::daemon
