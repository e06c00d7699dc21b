// rangefitd on the simulated cell, end to end: a separate rangefitd process runs the sim/ devices
// through fusion and the detectors and answers this test process over loopback DDS. CSS on the
// robot scans the bore plate (data/scenes/bore_plate.toml); the stripe cell scans the table-top
// scene of thesis fig. 5.18 (data/scenes/table_top_fig5_18.toml). Simulated time runs as fast as
// possible (sim.time_scale = 0).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "daemon/dds/client.hpp"
#include "sim/scene_loader.hpp"
#include "test/daemon/daemon_process.hpp"
#include "test/daemon/dds_test_env.hpp"

#ifdef RANGEFITD_PATH
namespace rangefit::daemon {
namespace sim_cell_e2e_test {
namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

const std::string kScenes = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/";

// What the test process saw for one request.
struct Observed {
  std::optional<DetectionResult> result;
  std::size_t cloud_points = 0;  // of the last cloud seen
  bool device_error = false;     // an ERROR diagnostic for the device run() was asked about
};

class SimCellDaemon {
 public:
  // css_extra: TOML lines appended to the css device (e.g. a [devices.sim_fault] table).
  SimCellDaemon(const std::string& test_name, const std::string& css_extra) {
    dir_ = fs::temp_directory_path() / ("rangefit_sim_e2e_" + test_name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    domain_ = test::dds_test_domain();  // also points CYCLONEDDS_URI at the loopback config
    std::ofstream(dir_ / "rangefitd.toml")
        << "[service]\nbore_sensor = \"css\"\nobject_sensor = \"stripe\"\nscan_timeout_s = 300\n"
        << "[dds]\ndomain_id = " << domain_ << "\ndiagnostics_period_s = 0.1\n"
        << "[spool]\ndirectory = \"" << (dir_ / "spool").string() << "\"\n"
        << "[detection]\ntimeout_s = 300\n"
        << "[sim]\ntime_scale = 0\nseed = 3\n"
        << "[[devices]]\nname = \"css\"\nkind = \"css\"\ndriver = \"sim\"\nscene = \"" << kScenes
        << "bore_plate.toml\"\n"
        << css_extra
        << "[[devices]]\nname = \"stripe\"\nkind = \"stripe\"\ndriver = \"sim\"\nscene = \""
        << kScenes << "table_top_fig5_18.toml\"\n"
        << "[[objects]]\nname = \"sphere\"\nscale_mm = [50, 50, 50]\nshape = [1.0, 1.0]\n"
        // Not in the scene: a flat tray, larger than anything on the table.
        << "[[objects]]\nname = \"tray\"\nscale_mm = [120, 90, 6]\nshape = [0.1, 0.1]\n";
    process_.emplace(RANGEFITD_PATH, dir_ / "rangefitd.toml");
    client_.emplace(domain_);
  }
  ~SimCellDaemon() {
    client_.reset();
    if (process_) process_->stop();
    fs::remove_all(dir_);
  }

  DdsClient& client() { return *client_; }
  int stop() {
    client_.reset();
    const int status = process_->stop();
    process_.reset();
    return status;
  }

  // Sends the request and collects its result, the cloud published with it and whether an
  // ERROR diagnostic named error_device arrived meanwhile.
  Observed run(const ScanRequest& request, const std::string& error_device = "") {
    Observed seen;
    EXPECT_TRUE(client_->send(request, false));
    const auto deadline = std::chrono::steady_clock::now() + seconds(240);
    std::optional<std::chrono::steady_clock::time_point> settle;
    DdsClient::Callbacks cb;
    cb.detection = [&](const DetectionResult& r) {
      if (r.request_id == request.id) seen.result = r;
    };
    cb.cloud = [&](const PointCloud& c) { seen.cloud_points = c.size(); };
    cb.diagnostics = [&](const std::vector<DiagStatus>& statuses) {
      for (const auto& s : statuses) {
        if (s.hardware_id == error_device && s.level == kDiagError) seen.device_error = true;
      }
    };
    while (std::chrono::steady_clock::now() < deadline) {
      client_->poll(milliseconds(100), cb);
      if (!seen.result) continue;
      if (!settle) settle = std::chrono::steady_clock::now() + seconds(3);
      const bool cloud_done = seen.cloud_points > 0 || seen.result->num_points == 0;
      const bool diag_done = error_device.empty() || seen.device_error;
      if ((cloud_done && diag_done) || std::chrono::steady_clock::now() > *settle) break;
    }
    return seen;
  }

 private:
  fs::path dir_;
  std::uint32_t domain_ = 0;
  std::optional<test::DaemonProcess> process_;
  std::optional<DdsClient> client_;
};

ScanRequest bore_request(const std::string& id, const sim::BoreTruth& truth) {
  ScanRequest r;
  r.id = id;
  r.kind = DetectKind::kBore;
  r.bore.position_mm = truth.opening_mm + Eigen::Vector3d(0.8, -0.5, 0.0);  // CAD vs. real part
  r.bore.axis = -truth.axis;  // out of the material, toward the sensor
  r.bore.radius_mm = 0.5 * truth.diameter_mm;
  return r;
}

ScanRequest object_request(const std::string& id, const std::string& model) {
  ScanRequest r;
  r.id = id;
  r.kind = DetectKind::kObject;
  r.model = model;
  return r;
}

// The bore under the CSS at omega = 0 (bore_plate.toml shifts the 12 mm one there).
sim::BoreTruth bore_under_sensor() {
  const sim::Scene plate = sim::load_scene(kScenes + "bore_plate.toml");
  for (const auto& b : plate.bores) {
    if (b.name == "straight_12") return b;
  }
  ADD_FAILURE() << "bore_plate.toml has no straight_12";
  return {};
}

TEST(SimulatedCellEndToEnd, AnswersBoreAndObjectRequestsFromAnotherProcessWithWholeClouds) {
  SimCellDaemon daemon("requests", "");
  ASSERT_TRUE(daemon.client().wait_for_daemon(seconds(30)));

  // CSS on the robot, bore plate: thesis 4.2 tolerances (entrance 0.3 mm, axis 0.5 deg).
  const sim::BoreTruth truth = bore_under_sensor();
  const Observed bore = daemon.run(bore_request("bore-1", truth));
  ASSERT_TRUE(bore.result) << "no result for the bore request";
  ASSERT_TRUE(bore.result->found) << bore.result->reason;
  EXPECT_NEAR(bore.result->bore_radius_mm, 6.0, 0.1);
  const Eigen::Isometry3d& T_bore = bore.result->parts.at(0).T_world_part;
  EXPECT_LT((T_bore.translation() - truth.opening_mm).norm(), 0.3);
  EXPECT_LT(
      std::acos(std::min(1.0, std::abs(T_bore.linear().col(2).dot(truth.axis)))) * 180.0 / M_PI,
      0.5);
  EXPECT_GT(bore.result->num_points, 50000u);
  EXPECT_EQ(bore.cloud_points, bore.result->num_points) << "the cloud arrives whole";
  EXPECT_FALSE(bore.result->spool_entry.empty());

  // Stripe cell, table-top scene: the sphere of fig. 5.18 within 3 mm (thesis table 5.3).
  const Observed sphere = daemon.run(object_request("sphere-1", "sphere"));
  ASSERT_TRUE(sphere.result) << "no result for the sphere request";
  ASSERT_TRUE(sphere.result->found) << sphere.result->reason;
  const Eigen::Vector3d centre = sphere.result->parts.at(0).T_world_part.translation();
  EXPECT_LT((centre - Eigen::Vector3d(160.0, 65.0, 50.0)).norm(), 3.0) << centre.transpose();
  EXPECT_GT(sphere.result->num_points, 50000u);
  EXPECT_EQ(sphere.cloud_points, sphere.result->num_points) << "the cloud arrives whole";

  // A configured model that is not in the scene: the detector's "not found" passes unchanged.
  const Observed tray = daemon.run(object_request("tray-1", "tray"));
  ASSERT_TRUE(tray.result) << "no result for the tray request";
  EXPECT_FALSE(tray.result->found) << "found a tray that is not in the scene";
  EXPECT_FALSE(tray.result->reason.empty());

  EXPECT_EQ(daemon.stop(), 0);
}

TEST(SimulatedCellEndToEnd, DeviceLostMidScanGivesAnErrorResultAndDiagnosticThenRecovers) {
  // The CSS's link drops 5 s into its first scan (simulated unplug) and is back for the next.
  SimCellDaemon daemon("fault",
                       "[devices.sim_fault]\ndisconnect_after_s = 5.0\n"
                       "disconnect_for_s = 2.0\non_scan = 1\n");
  ASSERT_TRUE(daemon.client().wait_for_daemon(seconds(30)));
  const sim::BoreTruth truth = bore_under_sensor();

  const Observed lost = daemon.run(bore_request("lost-1", truth), "css");
  ASSERT_TRUE(lost.result) << "no result for the interrupted scan";
  EXPECT_FALSE(lost.result->found);
  EXPECT_NE(lost.result->reason.find("scan failed"), std::string::npos) << lost.result->reason;
  EXPECT_NE(lost.result->reason.find("link lost"), std::string::npos) << lost.result->reason;
  EXPECT_TRUE(lost.device_error) << "no ERROR diagnostic for the css device";

  const Observed back = daemon.run(bore_request("back-1", truth));
  ASSERT_TRUE(back.result) << "no result after the device returned";
  ASSERT_TRUE(back.result->found) << back.result->reason;
  EXPECT_LT((back.result->parts.at(0).T_world_part.translation() - truth.opening_mm).norm(), 0.3);
  EXPECT_EQ(daemon.stop(), 0);
}

}  // namespace sim_cell_e2e_test
}  // namespace rangefit::daemon
#endif
