// Stripe-cell scan (thesis 5.2.1, fig. 5.8) through the real driver: the simulated drive moves
// the table at scan speed, the simulator casts the ranger's fan at the true axis position of each
// exposure, and fusion places each profile at the axis position interpolated from the driver's
// samples. The fused cloud must match the simulator's ground truth within the position
// uncertainty the round trips imply.
#include <gtest/gtest.h>

#include <cmath>

#include "fusion/profile_assembler.hpp"
#include "sim/ranger_simulator.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scene.hpp"
#include "test/drivers/modbus_test_rig.hpp"

namespace rangefit::test {
namespace modbus_stripe_cell_test {

// Table surface and a sphere on it, in the table ("world") frame the cell's cloud is built in.
sim::Scene cell_scene() {
  sim::Scene scene;
  scene.source = "modbus stripe-cell test";
  scene.objects.push_back({"table", sim::PlaneShape{600.0, 600.0}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.0, 0.0, 60.0);
  scene.objects.push_back({"ball", sim::SphereShape{60.0}, T});
  return scene;
}

TEST(FhppAxisStripeCell, ScanThroughTheDriverMatchesTheSimulatedTruthWithinTheRoundTrip) {
  const hal::StripeCellGeometry geometry;
  sim::SimAxisConfig drive_config = sim_axis_config();
  drive_config.max_mm = geometry.axis_travel_mm;
  ModbusRig rig(false, {}, drive_config);
  rig.config.poll_period = 10ms;  // as in the cell
  rig.config.travel.max_mm = geometry.axis_travel_mm;
  rig.start_streaming();
  rig.enable_and_home();
  ASSERT_TRUE(rig.axis->move_to(170.0, 500.0).ok);
  ASSERT_TRUE(wait_until([&] { return rig.axis->motion_complete(); }, 2s));
  std::vector<hal::AxisSample> axis;
  rig.axis->read(axis, 0ms);
  axis.clear();
  // Across the ball (table y = 200 - s passes 0 at s = 200), at 10 % of the drive's top speed.
  const double speed = 50.0;
  ASSERT_TRUE(rig.axis->move_to(230.0, speed).ok);
  ASSERT_TRUE(wait_until([&] { return rig.axis->motion_complete(); }, 3s));
  rig.axis->read(axis, 20ms);
  ASSERT_GE(axis.size(), 50u);

  // Profiles every 10 ms, exposed 3 ms after a poll, inside the constant-speed part of the scan.
  const sim::Scene scene = cell_scene();
  const sim::RayCaster caster(scene);
  fusion::StripeCellFusionConfig fusion_config;
  fusion_config.geometry = geometry;
  fusion_config.profile_period = 10ms;
  fusion::StripeCellAssembler assembler(fusion_config);
  for (const auto& a : axis) assembler.add_axis(a);
  std::vector<std::vector<Eigen::Vector3d>> truth;  // per profile, per column (NaN = none)
  double worst_uncertainty_s = 0.0;
  std::uint32_t sequence = 0;
  for (hal::Timestamp t = axis.front().stamp + 3ms; t < axis.back().stamp; t += 10ms) {
    const double s = rig.drive.position_at(t);
    if (s < 172.0 || s > 228.0) continue;
    const sim::ProfileTruth cast =
        sim::cast_profile(caster, geometry.ranger, geometry.T_world_ranger(s));
    hal::RangerProfile p;
    p.sequence = sequence++;
    p.stamp = t;
    // Ground truth: each profile point placed with the true axis position of its exposure.
    const Eigen::Isometry3d T_true = geometry.T_world_ranger(s);
    std::vector<Eigen::Vector3d> hits;
    for (std::size_t k = 0; k < cast.x_mm.size(); ++k) {
      const bool hit = !std::isnan(cast.x_mm[k]) && !std::isnan(cast.z_mm[k]);
      p.x_mm.push_back(hit ? static_cast<float>(cast.x_mm[k]) : hal::kNoReturn);
      p.z_mm.push_back(hit ? static_cast<float>(cast.z_mm[k]) : hal::kNoReturn);
      hits.push_back(hit ? Eigen::Vector3d(T_true * hal::StripeRanger::ranger_point(p.x_mm.back(),
                                                                                    p.z_mm.back()))
                         : Eigen::Vector3d::Constant(std::nan("")));
    }
    truth.push_back(hits);
    assembler.add_profile(p);
  }
  for (const auto& a : axis) {
    worst_uncertainty_s =
        std::max(worst_uncertainty_s, std::chrono::duration<double>(a.uncertainty).count());
  }
  const fusion::FusedScan scan = assembler.finish();
  ASSERT_GE(truth.size(), 80u);  // 56 mm at 50 mm/s, a profile per 10 ms
  ASSERT_EQ(scan.cloud.grid.rows, static_cast<int>(truth.size()));
  EXPECT_FALSE(scan.bad) << scan.reason;
  EXPECT_EQ(scan.faults.total(), 0u);

  // A position error ds moves every point of the profile by ds along the axis: the bound is the
  // stamp uncertainty at scan speed, one increment, and rounding.
  const double bound_mm = speed * worst_uncertainty_s / 2.0 + 1e-3 + 1e-4;
  double worst_mm = 0.0;
  std::size_t points = 0, on_ball = 0;
  for (int r = 0; r < scan.cloud.grid.rows; ++r) {
    for (int c = 0; c < scan.cloud.grid.cols; ++c) {
      const Eigen::Vector3d& hit = truth[r][c];
      const std::int32_t k = scan.cloud.grid.at(r, c);
      ASSERT_EQ(k >= 0, !std::isnan(hit.x()));
      if (k < 0) continue;
      worst_mm = std::max(worst_mm, (scan.cloud.points[k] - hit).norm());
      ++points;
      if (hit.z() > 1.0) ++on_ball;  // above the table surface
    }
  }
  EXPECT_LE(worst_mm, bound_mm) << "worst round trip " << worst_uncertainty_s * 1e6 << " us";
  EXPECT_GT(points, 10000u);
  EXPECT_GT(on_ball, 1000u);  // the ball was scanned, not only the table
}

}  // namespace modbus_stripe_cell_test
}  // namespace rangefit::test
