// Teaching and calibrating on the cell, through the service: a `learn` request on the simulated
// stripe cell learns the thesis cylinder lying on the table within the learning tests'
// one-view tolerances (2 % size, 0.1 shape) and leaves model.toml in the spool entry, which reads
// back as the model, the one `rangefit learn` writes from the spooled scan; a `calibrate` request
// over the hollow cube recovers the cell's stripe geometry and writes calibration_stripe.toml and
// its report, applying nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>

#include "calib/raw_sweep_text.hpp"
#include "calib/stripe_calibration.hpp"
#include "daemon/rangefitd/service.hpp"
#include "detect/common/angles.hpp"
#include "detect/learn/model_learning.hpp"
#include "io/object_model_file.hpp"
#include "sim/scene_objects.hpp"
#include "test/calib/calib_fixtures.hpp"
#include "test/daemon/cube_scene.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/detect/learn_scenes.hpp"

namespace rangefit::daemon {
namespace service_teach_test {
namespace fs = std::filesystem;

DaemonConfig stripe_cell(const fs::path& dir, const fs::path& scene) {
  DaemonConfig config;
  config.dds.domain_id = test::dds_test_domain();
  config.spool.directory = dir / "spool";
  config.spool.pictures = false;
  config.sim.time_scale = 0.0;
  config.sim.seed = 4;
  DeviceConfig stripe;
  stripe.name = stripe.kind = "stripe";
  stripe.scene = scene;
  config.devices.push_back(stripe);
  config.service.object_sensor = "stripe";
  return config;
}

// The noise-free stripe cell with the hollow cube at T_cube on its table. The sanitizer build
// takes 12-19 s for one camera's solve and about a minute for two: detection may take 300 s.
DaemonConfig cube_cell(const fs::path& dir, const Eigen::Isometry3d& T_cube) {
  test::write_cube_scene(dir / "cube.toml", 120.0, 12.0, T_cube, true);
  DaemonConfig config = stripe_cell(dir, dir / "cube.toml");
  config.sim.noise = false;
  config.detection.timeout_s = 300.0;
  return config;
}

// A stripe calibrate request over the hollow cube at T_cube on the table.
ScanRequest stripe_calibrate(const std::string& id, const Eigen::Isometry3d& T_cube) {
  ScanRequest req;
  req.id = id;
  req.kind = DetectKind::kCalibrate;
  req.target.kind = "stripe";
  req.target.T_table_target = T_cube;
  return req;
}

std::optional<DetectionResult> run(Service& service, const ScanRequest& req) {
  EXPECT_TRUE(service.board().reserve(req.id));
  if (const auto refused = service.admit(req)) return refused;
  return service.board().wait_for(req.id, std::chrono::seconds(120));
}

ScanRequest learn(const std::string& id, const std::string& model = "", std::uint64_t seed = 0) {
  ScanRequest req;
  req.id = id;
  req.kind = DetectKind::kLearn;
  req.model = model;
  req.seed = seed;
  return req;
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string without_comments(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("#")) out += line + "\n";
  }
  return out;
}

// The first learnt part's shape, from the result's details.
Superquadric learnt_shape(const DetectionResult& r) {
  const auto& part = r.details.at("parts").at(0);
  const auto& a = part.at("size");
  return {a.at(0).get<double>(),
          a.at(1).get<double>(),
          a.at(2).get<double>(),
          part.at("shape").at(0).get<double>(),
          part.at("shape").at(1).get<double>(),
          part.at("taper").at(0).get<double>(),
          part.at("taper").at(1).get<double>()};
}

// The stripe cell and a pan-tilt head named "head" on the same scene (which mounts the head).
DaemonConfig stripe_and_head(const fs::path& dir, const fs::path& scene) {
  DaemonConfig config = stripe_cell(dir, scene);
  DeviceConfig head;
  head.name = "head";
  head.kind = "pan_tilt";
  head.scene = scene;
  config.devices.push_back(head);
  return config;
}

TEST(ServiceTeach, LearnRequestLearnsTheCylinderOnTheStripeCell) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_learn");
  // The thesis cylinder (r 30, half length 50) lying along x. Standing, the stripe cell sees
  // its top and barely its sides, and one view leaves the height to the volume term (4.7 %
  // too tall, measured): the learning tests' views look at the side as well.
  const Superquadric truth = sim::cylinder_model();
  Eigen::Isometry3d T_truth = Eigen::Isometry3d::Identity();
  T_truth.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX())
          .toRotationMatrix();
  T_truth.translation() = Eigen::Vector3d(0, 0, truth.a1);
  std::ofstream(dir / "scene.toml")
      << "[[object]]\nname = \"table\"\ntype = \"plane\"\nsize = [1000, 1000]\n"
      << "[[object]]\nname = \"can\"\ntype = \"superquadric\"\nposition = [0, 0, " << truth.a1
      << "]\nz_axis = [1, 0, 0]\na = [" << truth.a1 << ", " << truth.a2 << ", " << truth.a3
      << "]\neps = [" << truth.eps1 << ", " << truth.eps2 << "]\n";
  const DaemonConfig config = stripe_cell(dir, dir / "scene.toml");
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  const auto result = run(service, learn("teach-can", "can", 2));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason;
  ASSERT_EQ(result->parts.size(), 1u);
  const auto& part = result->details.at("parts").at(0);
  const Superquadric learnt = learnt_shape(*result);
  const test::ShapeError e =
      test::shape_error(learnt, result->parts[0].T_world_part, truth, T_truth);
  EXPECT_LT(e.size, 0.02) << result->details.dump();
  EXPECT_LT(e.shape, 0.1) << result->details.dump();
  EXPECT_LT((result->parts[0].T_world_part.translation() - T_truth.translation()).norm(), 2.0);
  EXPECT_GT(part.at("residual_mm").get<double>(), 0.0);
  // The model file is in the entry, named in the result, and reads back as the learnt model.
  const fs::path file = result->details.at("files").at("model.toml").get<std::string>();
  EXPECT_EQ(file, fs::path(result->spool_entry) / "model.toml");
  const ObjectModel model = io::read_object_model(file);
  EXPECT_EQ(model.name, "can");
  ASSERT_EQ(model.parts.size(), 1u);
  EXPECT_NEAR(model.parts[0].shape.a1, learnt.a1, 1e-6);
  EXPECT_NE(text_of(file).find("residual"), std::string::npos);
#ifdef RANGEFIT_CLI_PATH
  // `rangefit learn` on the spooled scan writes the same model (its comments name the source).
  const std::string cli = std::string(RANGEFIT_CLI_PATH) + " learn --cloud " +
                          (fs::path(result->spool_entry) / "cloud.ply").string() +
                          " --seed 2 --name can --out " + (dir / "cli.toml").string() +
                          " > /dev/null";
  ASSERT_EQ(std::system(cli.c_str()), 0);
  EXPECT_EQ(without_comments(text_of(dir / "cli.toml")), without_comments(text_of(file)));
#endif
  fs::remove_all(dir);
}

// Teaching from two sensors at once (`rangefit learn --cloud A --cloud B` on the cell): the
// thesis cylinder standing on the table, scanned by the stripe cell's sweep from above and the
// pan-tilt head's sweep, their clouds fused in the world frame before learning (measured: size
// within 0.07 % fused, 0.35 % from the stripe cell alone).
TEST(ServiceTeach, LearnRequestFusesTheStripeCellAndThePanTiltHeadScans) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_learn_views");
  const Superquadric truth = sim::cylinder_model();
  Eigen::Isometry3d T_truth = Eigen::Isometry3d::Identity();
  T_truth.translation() = Eigen::Vector3d(0, 0, truth.a3);
  std::ofstream(dir / "scene.toml")
      << "[[object]]\nname = \"table\"\ntype = \"plane\"\nsize = [1000, 1000]\n"
      << "[[object]]\nname = \"can\"\ntype = \"superquadric\"\nposition = [0, 0, " << truth.a3
      << "]\na = [" << truth.a1 << ", " << truth.a2 << ", " << truth.a3 << "]\neps = ["
      << truth.eps1 << ", " << truth.eps2 << "]\n"
      << "[sensors.pantilt]\nposition = [0, 0, 700]\nrpy_deg = [180, 0, 0]\n";
  const DaemonConfig config = stripe_and_head(dir, dir / "scene.toml");
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  const ScanRequest one = learn("teach-stripe", "can", 2);
  ScanRequest both = learn("teach-both", "can", 2);
  both.sensors = {"stripe", "head"};
  const auto alone = run(service, one);
  const auto fused = run(service, both);
  loop.reset();
  ASSERT_TRUE(alone && fused);
  ASSERT_TRUE(fused->found) << fused->reason;
  EXPECT_EQ(fused->details.at("views").get<int>(), 2);
  EXPECT_GT(fused->num_points, alone->num_points);
  const test::ShapeError e =
      test::shape_error(learnt_shape(*fused), fused->parts[0].T_world_part, truth, T_truth);
  std::printf("  fused: size %.4f shape %.4f, %zu points\n", e.size, e.shape, fused->num_points);
  if (alone->found) {
    const test::ShapeError a =
        test::shape_error(learnt_shape(*alone), alone->parts[0].T_world_part, truth, T_truth);
    std::printf("  stripe alone: size %.4f shape %.4f, %zu points\n", a.size, a.shape,
                alone->num_points);
  }
  EXPECT_LT(e.size, 0.02) << fused->details.dump();
  EXPECT_LT(e.shape, 0.1) << fused->details.dump();
  // The model file says where it came from.
  const fs::path file = fused->details.at("files").at("model.toml").get<std::string>();
  EXPECT_NE(text_of(file).find("on stripe + head"), std::string::npos) << text_of(file);
  fs::remove_all(dir);
}

// A sensor lost during its scan fails the fused learn with its name and reason; the scans taken
// before it are kept in the spool entry.
TEST(ServiceTeach, ASensorLostDuringAFusedLearnFailsItAndTheEarlierScanIsKept) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_learn_views_lost");
  std::ofstream(dir / "scene.toml")
      << "[[object]]\nname = \"table\"\ntype = \"plane\"\nsize = [1000, 1000]\n"
      << "[[object]]\nname = \"box\"\ntype = \"box\"\nsize = [60, 40, 30]\n"
      << "position = [0, 0, 15]\n[sensors.pantilt]\nposition = [0, 0, 700]\n"
      << "rpy_deg = [180, 0, 0]\n";
  DaemonConfig config = stripe_and_head(dir, dir / "scene.toml");
  SimFaultConfig& fault = config.devices.back().sim_fault;
  fault.disconnect_after_s = 0.1;  // unplugged at once, and for good
  fault.disconnect_for_s = 1e6;
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  ScanRequest req = learn("teach-lost");
  req.sensors = {"stripe", "head"};
  const auto result = run(service, req);
  loop.reset();
  ASSERT_TRUE(result);
  EXPECT_FALSE(result->found);
  EXPECT_NE(result->reason.find("scan failed: head: "), std::string::npos) << result->reason;
  EXPECT_GT(result->num_points, 10000u);  // the stripe cell's scan
  ASSERT_FALSE(result->spool_entry.empty());
  EXPECT_GT(fs::file_size(fs::path(result->spool_entry) / "cloud.ply"), 100000u);
  fs::remove_all(dir);
}

TEST(ServiceTeach, LearnOnAnEmptyTableIsNotFound) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_learn_empty");
  std::ofstream(dir / "scene.toml") << "[[object]]\nname = \"table\"\ntype = \"plane\"\n";
  const DaemonConfig config = stripe_cell(dir, dir / "scene.toml");
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  const auto result = run(service, learn("teach-nothing"));
  loop.reset();
  ASSERT_TRUE(result);
  EXPECT_FALSE(result->found);
  EXPECT_EQ(result->reason, to_string(LearnReason::kNoObject));
  EXPECT_FALSE(fs::exists(fs::path(result->spool_entry) / "model.toml"));
  fs::remove_all(dir);
}

TEST(ServiceTeach, CalibrateRequestRecoversTheStripeCellAndAppliesNothing) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_calibrate");
  // Held on a corner, a body diagonal tilted toward the ranger.
  const Eigen::Isometry3d T_cube = test::cube_on_table();
  DaemonConfig config = cube_cell(dir, T_cube);
  hal::MonotonicClock clock;
  Service service(config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  const auto result = run(service, stripe_calibrate("calibrate-stripe", T_cube));
  loop.reset();
  ASSERT_TRUE(result);
  ASSERT_TRUE(result->found) << result->reason << " " << result->details.dump();
  EXPECT_FALSE(result->details.at("applied").get<bool>());
  EXPECT_LT(result->details.at("rms_mm").get<double>(), 0.05);
  // The simulated cell runs on the configured geometry: the calibration must come back to it.
  const hal::StripeCellGeometry truth = config.fusion.stripe_cell.geometry;
  const auto& f = result->details.at("fusion.stripe_cell");
  const auto v = [](const nlohmann::json& j) {
    return Eigen::Vector3d(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
  };
  EXPECT_LT((v(f.at("ranger_position_cell_mm")) - truth.ranger_position_cell_mm).norm(), 0.05);
  EXPECT_LT((v(f.at("ranger_rpy_cell_rad")) - truth.ranger_rpy_cell_rad).norm(), 0.01 * kDeg);
  EXPECT_LT(
      std::acos(std::min(
          1.0,
          v(f.at("axis_direction_cell")).normalized().dot(truth.axis_direction_cell.normalized()))),
      0.01 * kDeg);
  const auto& files = result->details.at("files");
  const fs::path toml = files.at("calibration_stripe.toml").get<std::string>();
  const fs::path report = files.at("calibration_stripe.toml.report.txt").get<std::string>();
  EXPECT_EQ(toml.parent_path(), fs::path(result->spool_entry));
  EXPECT_NE(text_of(toml).find("[fusion.stripe_cell]"), std::string::npos);
  EXPECT_NE(text_of(report).find("refinement"), std::string::npos);
  // Never applied: the running configuration is the one it started with.
  EXPECT_EQ(service.config_copy().fusion.stripe_cell.geometry.ranger_position_cell_mm,
            truth.ranger_position_cell_mm);
  fs::remove_all(dir);
}

// The cube cell with a second camera "stripe_b" of its laser plane, on the other side of it, in
// its own frame of the plane: turned 2 deg about the plane's normal, shifted 6 and -5 mm.
DaemonConfig two_camera_cube_cell(const fs::path& dir, const Eigen::Isometry3d& T_cube) {
  DaemonConfig config = cube_cell(dir, T_cube);
  DeviceConfig b = config.devices.front();
  b.name = "stripe_b";
  config.devices.push_back(b);
  Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
  P.linear() = Eigen::AngleAxisd(2.0 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  P.translation() = Eigen::Vector3d(6.0, 0.0, -5.0);
  const hal::StripeCellGeometry a = config.fusion.stripe_cell.geometry;
  const Eigen::Isometry3d T_b = a.T_cell_ranger() * P;
  config.fusion.stripe_cell.cameras.push_back({"stripe_b", T_b.translation(),
                                               calib::rpy_of(T_b.linear(), a.ranger_rpy_cell_rad),
                                               -a.ranger.baseline_mm});
  return config;
}

// Each camera of the rig result came back to the configured cell within 0.05 mm / 0.01 deg.
void expect_both_cameras_calibrated(const DetectionResult& r, const DaemonConfig& config) {
  EXPECT_EQ(r.details.at("cameras").get<int>(), 2);
  const auto v = [](const nlohmann::json& j) {
    return Eigen::Vector3d(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
  };
  const auto& cams = r.details.at("stripe_cameras");
  ASSERT_EQ(cams.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const hal::StripeCellGeometry truth =
        fusion::stripe_cell_for(config.fusion.stripe_cell, k == 0 ? "stripe" : "stripe_b").geometry;
    SCOPED_TRACE(cams[k].dump());
    EXPECT_EQ(cams[k].at("sensor").get<std::string>(), k == 0 ? "stripe" : "stripe_b");
    EXPECT_LT((v(cams[k].at("ranger_position_cell_mm")) - truth.ranger_position_cell_mm).norm(),
              0.05);
    EXPECT_LT((v(cams[k].at("ranger_rpy_cell_rad")) - truth.ranger_rpy_cell_rad).norm(),
              0.01 * kDeg);
  }
  const auto& files = r.details.at("files");
  const std::string toml = text_of(files.at("calibration_stripe.toml").get<std::string>());
  EXPECT_NE(toml.find("[[fusion.stripe_cell.cameras]]"), std::string::npos) << toml;
  EXPECT_NE(toml.find("name = \"stripe_b\""), std::string::npos) << toml;
  EXPECT_NE(text_of(files.at("calibration_stripe.toml.report.txt").get<std::string>())
                .find("piercing points averaged"),
            std::string::npos);
}

// The service on the two-camera cube cell, the cube's body diagonal straight up towards the
// laser (both sides see its three outer faces), answering requests until stop().
struct TwoCameraCubeService {
  explicit TwoCameraCubeService(const char* name)
      : dir(test::fresh_test_dir(name)),
        T_cube(test::cube_between_cameras()),
        config(two_camera_cube_cell(dir, T_cube)),
        service(config, clock),
        loop(std::make_unique<test::ServiceLoop>(service)) {}
  ~TwoCameraCubeService() { fs::remove_all(dir); }
  void stop() { loop.reset(); }

  fs::path dir;
  Eigen::Isometry3d T_cube;
  DaemonConfig config;
  hal::MonotonicClock clock;
  Service service;
  std::unique_ptr<test::ServiceLoop> loop;
};

// Two cameras of one laser plane, one on each side of it: each sweeps the cube in a request of
// its own, the second names the first, and both come back to the configured cell together.
TEST(ServiceTeach, TwoCamerasOfOneLaserPlaneCalibrateTogether) {
  TwoCameraCubeService cell("rangefit_service_calibrate_rig");
  ScanRequest req = stripe_calibrate("calibrate-a", cell.T_cube);
  req.sensor = "stripe";
  const auto first = run(cell.service, req);
  req.id = "calibrate-b";
  req.sensor = "stripe_b";
  req.target.scans = {"calibrate-a"};
  const auto both = run(cell.service, req);
  req.id = "calibrate-b-again";  // the same camera twice is no rig
  req.target.scans = {"calibrate-b"};
  const auto twice = run(cell.service, req);
  cell.stop();
  ASSERT_TRUE(first && both && twice);
  ASSERT_TRUE(first->found) << first->reason;  // the first camera on its own, as before
  ASSERT_TRUE(both->found) << both->reason << " " << both->details.dump();
  expect_both_cameras_calibrated(*both, cell.config);
  EXPECT_TRUE(fs::exists(both->details.at("files").at("raw_sweep_stripe.txt").get<std::string>()));
  EXPECT_FALSE(twice->found);
  EXPECT_NE(twice->reason.find("one sweep per camera"), std::string::npos) << twice->reason;
}

// One request names both cameras: they sweep the cube together (one axis), each camera's sweep
// is spooled as the file `rangefit calibrate stripe --scans` reads, and they are solved as one
// rig. A later request with the first camera alone that names it is the same camera twice.
TEST(ServiceTeach, TwoCamerasOfOneLaserPlaneCalibrateInOneRequest) {
  TwoCameraCubeService cell("rangefit_service_calibrate_rig_one");
  ScanRequest req = stripe_calibrate("calibrate-ab", cell.T_cube);
  req.sensors = {"stripe", "stripe_b"};
  const auto both = run(cell.service, req);
  req.id = "calibrate-a-again";
  req.sensors.clear();
  req.sensor = "stripe";
  req.target.scans = {"calibrate-ab"};
  const auto twice = run(cell.service, req);
  cell.stop();
  ASSERT_TRUE(both && twice);
  ASSERT_TRUE(both->found) << both->reason << " " << both->details.dump();
  expect_both_cameras_calibrated(*both, cell.config);
  const auto& files = both->details.at("files");
  for (const char* name : {"raw_sweep_stripe.txt", "raw_sweep_stripe_2.txt"}) {
    SCOPED_TRACE(name);
    const calib::RawSweepParse sweep =
        calib::parse_raw_sweep(text_of(files.at(name).get<std::string>()));
    ASSERT_TRUE(sweep.sweep) << sweep.error;
    EXPECT_GT(sweep.sweep->profiles.size(), 100u);
  }
  EXPECT_NE(
      text_of(files.at("calibration_stripe.toml").get<std::string>()).find("on stripe, stripe_b"),
      std::string::npos);
  EXPECT_FALSE(twice->found);
  EXPECT_NE(twice->reason.find("one sweep per camera"), std::string::npos) << twice->reason;
}

TEST(ServiceTeach, CalibrateRefusesATargetItCannotScanAndASensorOfAnotherKind) {
  const fs::path dir = test::fresh_test_dir("rangefit_service_calibrate_refused");
  std::ofstream(dir / "scene.toml") << "[[object]]\nname = \"table\"\ntype = \"plane\"\n";
  const DaemonConfig config = stripe_cell(dir, dir / "scene.toml");
  hal::MonotonicClock clock;
  Service service(config, clock);
  ScanRequest req;
  req.id = "calibrate-robot";  // a device the service does not calibrate
  req.kind = DetectKind::kCalibrate;
  req.target.kind = "robot";
  const auto refused = service.admit(req);
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->reason.find("calibrate target must be \"stripe\""), std::string::npos)
      << refused->reason;
  fs::remove_all(dir);
}

}  // namespace service_teach_test
}  // namespace rangefit::daemon
