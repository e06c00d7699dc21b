// rangefitd's DDS face, in-process, over a loopback-only Cyclone configuration on a random
// domain: requests in, results, clouds and diagnostics out, as a separate client sees them.
#include "daemon/rangefitd/service.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "daemon/dds/client.hpp"
#include "io/ply.hpp"
#include "test/daemon/fakes.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace dds_service_test {
namespace fs = std::filesystem;

class DdsServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_dir(fs::path("rangefit_dds_service_test") /
                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
    config_ = test::replay_css_config(dir_, dir_ / "scan.ply");
    config_.dds.diagnostics_period_s = 0.1;
    config_.objects.push_back(inline_object("box", {40, 30, 20}, {0.1, 0.1}));
  }
  void TearDown() override {
    loop_.reset();
    service_.reset();
    fs::remove_all(dir_);
  }
  void start(std::unique_ptr<ScanBackend> backend, std::unique_ptr<Detector> detector) {
    service_ = std::make_unique<Service>(config_, clock_, std::move(backend), std::move(detector));
    loop_ = std::make_unique<test::ServiceLoop>(*service_);
  }
  ScanRequest bore(const std::string& id) {
    ScanRequest r;
    r.id = id;
    r.kind = DetectKind::kBore;
    r.bore.radius_mm = 5;
    return r;
  }

  fs::path dir_;
  DaemonConfig config_;
  hal::MonotonicClock clock_;
  std::unique_ptr<Service> service_;
  std::unique_ptr<test::ServiceLoop> loop_;
};

TEST_F(DdsServiceTest, RequestGetsItsResultInMetresAndTheCloudArrivesWhole) {
  auto backend = std::make_unique<test::FakeBackend>();
  backend->points = 140000;
  start(std::move(backend), std::make_unique<test::CentroidDetector>());
  DdsClient client(config_.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  std::size_t cloud_points = 0;
  ASSERT_TRUE(client.send(bore("e2e-1"), false));
  const auto result = client.wait_result("e2e-1", std::chrono::seconds(30));
  ASSERT_TRUE(result);
  EXPECT_TRUE(result->found) << result->reason;
  EXPECT_EQ(result->num_points, 140000u);
  // The centroid of grid_cloud(140000), converted mm → m → mm through the wire.
  const Eigen::Vector3d expected(4.5, 4.5, 0.5 * (140000 - 1) / 2.0);
  EXPECT_TRUE(result->parts.at(0).T_world_part.translation().isApprox(expected, 1e-9));
  EXPECT_TRUE(fs::exists(result->spool_entry));
  for (int i = 0; i < 50 && cloud_points == 0; ++i) {
    client.poll(std::chrono::milliseconds(100),
                {.cloud = [&](const PointCloud& c) { cloud_points = c.size(); }});
  }
  EXPECT_EQ(cloud_points, 140000u);
}

TEST_F(DdsServiceTest, MalformedAndUnknownRequestsGetAnErrorResult) {
  start(std::make_unique<test::FakeBackend>(), std::make_unique<test::CentroidDetector>());
  DdsClient client(config_.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  ScanRequest bad_radius = bore("bad-radius");
  bad_radius.bore.radius_mm = 0;
  ScanRequest unknown_model = bore("unknown-model");
  unknown_model.kind = DetectKind::kObject;
  unknown_model.model = "teapot";
  ScanRequest unknown_sensor = bore("unknown-sensor");
  unknown_sensor.sensor = "lidar";
  for (const auto* r : {&bad_radius, &unknown_model, &unknown_sensor}) {
    ASSERT_TRUE(client.send(*r, false));
    const auto result = client.wait_result(r->id, std::chrono::seconds(30));
    ASSERT_TRUE(result) << r->id;
    EXPECT_FALSE(result->found);
    EXPECT_EQ(result->reason.rfind("bad request: ", 0), 0u) << result->reason;
  }
}

TEST_F(DdsServiceTest, ReplayDeviceGoneGivesErrorResultAndErrorDiagnosticThenRecovers) {
  start(nullptr, nullptr);  // the real DeviceBackend with the replay driver
  DdsClient client(config_.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  ASSERT_TRUE(client.send(bore("gone"), false));
  auto result = client.wait_result("gone", std::chrono::seconds(30));
  ASSERT_TRUE(result);
  EXPECT_FALSE(result->found);
  EXPECT_NE(result->reason.find("scan failed"), std::string::npos) << result->reason;

  bool device_error = false;
  for (int i = 0; i < 100 && !device_error; ++i) {
    client.poll(std::chrono::milliseconds(50),
                {.diagnostics = [&](const std::vector<DiagStatus>& s) {
                  for (const auto& d : s) {
                    if (d.hardware_id == "css" && d.level == kDiagError) device_error = true;
                  }
                }});
  }
  EXPECT_TRUE(device_error);

  io::write_ply(dir_ / "scan.ply", test::grid_cloud(500));  // the device is back
  ASSERT_TRUE(client.send(bore("back"), false));
  result = client.wait_result("back", std::chrono::seconds(30));
  ASSERT_TRUE(result);
  EXPECT_EQ(result->num_points, 500u);
  // The scan works again; the bore detector decides on the (flat grid) cloud by itself.
  EXPECT_EQ(result->reason.find("scan failed"), std::string::npos) << result->reason;
}

// rt/diagnostics comes once a period (REP 107: ~1 Hz), and at once when a device changes state:
// an outage shorter than the period still reaches a monitor, and so does the recovery.
TEST_F(DdsServiceTest, ADeviceStateChangeIsPublishedAtOnceNotAtTheNextPeriod) {
  config_.dds.diagnostics_period_s = 60.0;
  auto owned = std::make_unique<test::FakeBackend>();
  test::FakeBackend& backend = *owned;
  start(std::move(owned), std::make_unique<test::CentroidDetector>());
  DdsClient client(config_.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(20)));
  // The css level as the client last saw it, -1 before any message; polled for up to 10 s.
  int level = -1;
  const auto wait_level = [&](int want) {
    for (int i = 0; i < 200 && level != want; ++i) {
      client.poll(std::chrono::milliseconds(50),
                  {.diagnostics = [&](const std::vector<DiagStatus>& s) {
                    for (const auto& d : s) {
                      if (d.hardware_id == "css") level = d.level;
                    }
                  }});
    }
    return level == want;
  };
  backend.present = false;
  EXPECT_TRUE(wait_level(kDiagError)) << "last css level " << level;
  backend.present = true;
  EXPECT_TRUE(wait_level(kDiagOk)) << "last css level " << level;
}

}  // namespace dds_service_test
}  // namespace rangefit::daemon
