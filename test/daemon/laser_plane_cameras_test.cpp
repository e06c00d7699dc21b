// Two cameras of one laser plane on one axis or one pan-tilt head (driver = "sim"): an object
// request that names both is one sweep, not one per camera, and each camera's profiles are fused
// with its own geometry. A camera that loses its link mid-sweep fails the request naming it, and
// the service goes on.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "daemon/cell/device_backend.hpp"

namespace rangefit::daemon {
namespace laser_plane_cameras_test {

// Two simulated devices of `kind` over the fig. 5.18 table top, without noise.
DaemonConfig two_devices(const char* kind, const char* a, const char* b) {
  DaemonConfig c;
  c.sim.time_scale = 0.0;
  c.sim.noise = false;
  for (const char* name : {a, b}) {
    DeviceConfig d;
    d.name = name;
    d.kind = kind;
    d.scene = std::filesystem::path(RANGEFIT_SOURCE_DIR) / "data/scenes/table_top_fig5_18.toml";
    c.devices.push_back(d);
  }
  return c;
}

DaemonConfig two_camera_config() {
  DaemonConfig c = two_devices("stripe", "stripe", "stripe_b");
  for (DeviceConfig& d : c.devices) {
    d.sweep_start = 150.0;
    d.sweep_end = 230.0;
  }
  // The second camera is the first mirrored across the laser plane.
  const hal::StripeCellGeometry& g = c.fusion.stripe_cell.geometry;
  c.fusion.stripe_cell.cameras.push_back(
      {"stripe_b", g.ranger_position_cell_mm, g.ranger_rpy_cell_rad, -g.ranger.baseline_mm});
  return c;
}

ScanRequest object_request(std::vector<std::string> sensors) {
  ScanRequest r;
  r.kind = DetectKind::kObject;
  if (sensors.size() == 1) {  // the configured sweep, as the service plans it
    r.sensor = sensors.front();
    r.sweep_start = 150.0;
    r.sweep_end = 230.0;
  } else {
    r.sensors = std::move(sensors);
  }
  return r;
}

double stamp_span_s(const PointCloud& cloud) {
  const auto [lo, hi] = std::minmax_element(cloud.stamps.begin(), cloud.stamps.end());
  return std::chrono::duration<double>(*hi - *lo).count();
}

const hal::DeviceHealth* find(const std::vector<NamedHealth>& all, const std::string& name) {
  for (const auto& h : all) {
    if (h.name == name) return &h.health;
  }
  return nullptr;
}

TEST(StripeCameras, BothCamerasOfOneAxisScanInOneSweep) {
  DeviceBackend backend(two_camera_config());
  std::atomic<bool> cancel{false};
  const std::function<void()> progress = [] {};
  const ScanOutcome first = backend.scan(object_request({"stripe"}), cancel, progress);
  const ScanOutcome second = backend.scan(object_request({"stripe_b"}), cancel, progress);
  const std::vector<NamedHealth> before = backend.health();
  const ScanOutcome both = backend.scan(object_request({"stripe", "stripe_b"}), cancel, progress);
  ASSERT_TRUE(first.status && second.status) << first.status.message << second.status.message;
  ASSERT_TRUE(both.status) << both.status.message;
  ASSERT_TRUE(first.cloud.has_stamps() && both.cloud.has_stamps());

  // Every point either camera sees alone, from one pass of the table: the 80 mm at 6.3 mm/s
  // take 12.7 s; two sweeps in turn would span twice that and the move back between them.
  const auto alone = static_cast<double>(first.cloud.size() + second.cloud.size());
  EXPECT_NEAR(static_cast<double>(both.cloud.size()), alone, 0.01 * alone);
  EXPECT_LT(stamp_span_s(both.cloud), 1.05 * stamp_span_s(first.cloud));
  EXPECT_GT(both.sensor.view.second_camera_offset.norm(), 0.0) << "the view has both cameras";

  // Only the first device's axis moved; the second camera streamed its profiles.
  const std::vector<NamedHealth> after = backend.health();
  const auto samples = [](const std::vector<NamedHealth>& all, const std::string& name) {
    const hal::DeviceHealth* h = find(all, name);
    return h == nullptr ? 0 : h->counters.samples;
  };
  EXPECT_GT(samples(after, "stripe/axis"), samples(before, "stripe/axis"));
  EXPECT_EQ(samples(after, "stripe_b/axis"), samples(before, "stripe_b/axis"));
  EXPECT_GT(samples(after, "stripe_b"), samples(before, "stripe_b"));
  EXPECT_EQ(find(after, "stripe_b")->state, hal::DeviceState::kReady);
}

TEST(StripeCameras, ASecondCameraLostMidSweepFailsTheRequestNamingItAndTheNextScanWorks) {
  DaemonConfig config = two_camera_config();
  config.devices[1].sim_fault.disconnect_after_s = 3.0;
  config.devices[1].sim_fault.disconnect_for_s = 1.0;
  config.devices[1].sim_fault.on_scan = 1;
  DeviceBackend backend(config);
  std::atomic<bool> cancel{false};
  const std::function<void()> progress = [] {};
  const ScanOutcome lost = backend.scan(object_request({"stripe", "stripe_b"}), cancel, progress);
  EXPECT_FALSE(lost.status);
  EXPECT_NE(lost.status.message.find("stripe_b: sim-stripe-ranger: link lost"), std::string::npos)
      << lost.status.message;
  const std::vector<NamedHealth> health = backend.health();
  const hal::DeviceHealth* h = find(health, "stripe_b");
  ASSERT_NE(h, nullptr);
  EXPECT_EQ(h->state, hal::DeviceState::kDisconnected);
  const ScanOutcome again = backend.scan(object_request({"stripe", "stripe_b"}), cancel, progress);
  EXPECT_TRUE(again.status) << again.status.message;
  EXPECT_GT(again.cloud.size(), 10000u);
}

TEST(StripeCameras, CamerasOverDifferentScenesScanInTurn) {
  DaemonConfig config = two_camera_config();
  config.devices[1].scene =
      std::filesystem::path(RANGEFIT_SOURCE_DIR) / "data/scenes/cluttered_mallet.toml";
  DeviceBackend backend(config);
  std::atomic<bool> cancel{false};
  const std::function<void()> progress = [] {};
  const ScanOutcome first = backend.scan(object_request({"stripe"}), cancel, progress);
  const ScanOutcome both = backend.scan(object_request({"stripe", "stripe_b"}), cancel, progress);
  ASSERT_TRUE(first.status && both.status) << first.status.message << both.status.message;
  EXPECT_GT(stamp_span_s(both.cloud), 2.0 * stamp_span_s(first.cloud))
      << "two simulated cells: two sweeps";
}

TEST(PanTiltCameras, BothCamerasOfOneHeadScanInOneSweep) {
  DaemonConfig config = two_devices("pan_tilt", "head", "head_b");
  config.devices[1].motion = "head";
  config.fusion.pan_tilt.cameras.push_back(
      {"head_b", -config.fusion.pan_tilt.geometry.ranger.baseline_mm});
  DeviceBackend backend(config);
  std::atomic<bool> cancel{false};
  const std::function<void()> progress = [] {};
  ScanRequest one;
  one.kind = DetectKind::kObject;
  one.sensor = "head";
  const ScanOutcome first = backend.scan(one, cancel, progress);
  one.sensor = "head_b";
  const ScanOutcome second = backend.scan(one, cancel, progress);
  const ScanOutcome both = backend.scan(object_request({"head", "head_b"}), cancel, progress);
  ASSERT_TRUE(first.status && second.status && both.status)
      << first.status.message << second.status.message << both.status.message;
  // The mirrored camera sees what the first has in its shadow, and the other way round.
  const auto alone = static_cast<double>(first.cloud.size() + second.cloud.size());
  EXPECT_NEAR(static_cast<double>(both.cloud.size()), alone, 0.01 * alone);
  EXPECT_NE(first.cloud.size(), second.cloud.size());
  EXPECT_LT(stamp_span_s(both.cloud), 1.05 * stamp_span_s(first.cloud));
  EXPECT_GT(both.sensor.view.second_camera_offset.norm(), 0.0) << "the view has both cameras";
}

}  // namespace laser_plane_cameras_test
}  // namespace rangefit::daemon
