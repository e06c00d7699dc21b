// daemon/scan_sensor: the visibility model the service hands the object detector describes the
// sweep that measured the scan. Checked on points the simulated stripe cell measured: every point
// has a sweep position where the laser plane held it, the points of one profile agree on it, it
// advances with the axis, and the apex and camera sit where the cell's geometry puts them.
#include "daemon/service/scan_sensor.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <map>

#include "daemon/cell/sim_cell.hpp"

namespace rangefit::daemon {
namespace scan_sensor_test {

TEST(ScanSensor, StripeSweepHoldsEveryPointTheSimulatedCellMeasured) {
  DaemonConfig c;
  c.sim.time_scale = 0.0;
  c.sim.noise = false;
  DeviceConfig d;
  d.name = d.kind = "stripe";
  d.scene = std::filesystem::path(RANGEFIT_SOURCE_DIR) / "data/scenes/cluttered_mallet.toml";
  c.devices.push_back(d);
  SimCell cell(c);
  ScanRequest r;
  r.sweep_start = 100.0;  // axis mm; the table moves, the laser plane crosses table y ~ 100
  r.sweep_end = 110.0;
  r.sweep_speed = 6.3;
  std::atomic<bool> cancel{false};
  const ScanOutcome out = cell.scan(*c.device("stripe"), r, cancel, [] {});
  ASSERT_TRUE(out.status) << out.status.message;
  ASSERT_TRUE(out.cloud.has_stamps());
  ASSERT_GT(out.cloud.size(), 1000u);
  const SensorView& v = out.sensor.view;
  ASSERT_EQ(v.kind, SensorView::Kind::kLinearSweep);
  ASSERT_TRUE(valid(v));
  EXPECT_DOUBLE_EQ(v.sweep_min, 100.0);
  EXPECT_DOUBLE_EQ(v.sweep_max, 110.0);

  const hal::StripeCellGeometry g = c.fusion.stripe_cell.geometry;
  std::map<std::int64_t, std::pair<double, double>> s_by_stamp;  // min, max sweep position
  for (std::size_t i = 0; i < out.cloud.size(); ++i) {
    const Eigen::Vector3d& p = out.cloud.points[i];
    const Eyes eyes = sensor_eyes(v, p);
    ASSERT_EQ(eyes.count, 2) << "point " << i << " outside the sweep";
    const double s = (eyes.at[0] - v.origin).dot(v.direction);
    auto [it, fresh] = s_by_stamp.try_emplace(out.cloud.stamps[i].count(), s, s);
    it->second.first = std::min(it->second.first, s);
    it->second.second = std::max(it->second.second, s);
    // The scene puts the table surface at z = 0: apex 600 mm above, camera beside it.
    EXPECT_NEAR(eyes.at[0].z(), g.ranger_position_cell_mm.z(), 1e-6);
    EXPECT_NEAR((eyes.at[1] - eyes.at[0]).norm(), g.ranger.baseline_mm, 1e-6);
    // Inside the fan: at most half the fan angle from straight down.
    const Eigen::Vector3d ray = (p - eyes.at[0]).normalized();
    EXPECT_LT(std::acos(-ray.z()), 0.5 * g.ranger.fan_angle_rad + 1e-3);
  }
  ASSERT_GT(s_by_stamp.size(), 5u);
  // One profile, one sweep position (the axis quantises to 0.05 mm; fusion interpolates).
  for (const auto& [stamp, range] : s_by_stamp) EXPECT_LT(range.second - range.first, 1e-6);
  // It advances with the axis at the commanded speed: direction and sign agree with the cell.
  const auto& first = *s_by_stamp.begin();
  const auto& last = *s_by_stamp.rbegin();
  const double dt = static_cast<double>(last.first - first.first) * 1e-9;
  EXPECT_NEAR((last.second.first - first.second.first) / dt, 6.3, 0.1);
  EXPECT_NEAR(first.second.first, 100.0, 1.0);
  EXPECT_NEAR(last.second.first, 110.0, 1.0);
}

TEST(ScanSensor, MovingTheScanMovesTheSensorWithIt) {
  const ScanSensor s = stripe_sensor(hal::StripeCellGeometry{}, 0.0, 400.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(10, -20, 5);
  const Eigen::Vector3d p(30, 40, 20);
  const Eyes before = sensor_eyes(s.view, p);
  const Eyes after = sensor_eyes(transformed(s, T).view, T * p);
  ASSERT_EQ(before.count, 2);
  ASSERT_EQ(after.count, 2);
  for (int k = 0; k < 2; ++k) EXPECT_LT((T * before.at[k] - after.at[k]).norm(), 1e-9);
}

}  // namespace scan_sensor_test
}  // namespace rangefit::daemon
