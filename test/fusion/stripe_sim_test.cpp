// The stripe-cell assembler against the simulated sensor cell (sim/stripe_cell.hpp): the axis
// carries a sphere on the table through the laser plane; every fused point is compared with the
// exact ray-cast hit of its fan ray at the profile's exposure centre.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "fusion/profile_assembler.hpp"
#include "sim/ranger_simulator.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::fusion {
namespace stripe_sim_test {

using std::chrono::milliseconds;

TEST(StripeCellAssemblerOnSimulator, EveryFusedPointIsWithinAMicrometreOfTheRayCastHit) {
  sim::Scene scene;  // scene frame = table frame (mounts identity)
  scene.objects.push_back({"table", sim::PlaneShape{400.0, 400.0}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d ball = Eigen::Isometry3d::Identity();
  ball.translation() = Eigen::Vector3d(20.0, 185.0, 30.0);
  scene.objects.push_back({"ball", sim::SphereShape{30.0}, ball});
  const sim::RayCaster caster(scene);
  sim::SimClock clock;
  sim::StripeCellOptions options;
  options.quantise = false;           // exactness: no chip rows
  options.axis_resolution_mm = 1e-9;  // nor axis encoder steps
  sim::StripeCell cell(scene, caster, options, clock);
  StripeCellFusionConfig config;
  config.geometry = options.geometry;
  StripeCellAssembler assembler(config);

  const hal::Timestamp start = clock.now();
  const double travel_mm = 30.0, speed_mm_s = 6.3;
  const hal::Timestamp motion_end =
      start + hal::Duration(static_cast<std::int64_t>(travel_mm / speed_mm_s * 1e9));
  ASSERT_TRUE(cell.axis().enable());
  ASSERT_TRUE(cell.axis().move_to(travel_mm, speed_mm_s));
  ASSERT_TRUE(cell.ranger().start());
  ASSERT_TRUE(cell.axis().start());
  std::vector<hal::RangerProfile> profiles;
  std::vector<hal::AxisSample> axis;
  while (clock.now() < motion_end) {
    profiles.clear();
    axis.clear();
    cell.ranger().read(profiles, milliseconds(500));
    cell.axis().read(axis, milliseconds(0));
    for (const auto& a : axis) assembler.add_axis(a);
    for (const auto& p : profiles) assembler.add_profile(p);
  }
  const FusedScan scan = assembler.finish();
  EXPECT_EQ(scan.faults.out_of_order + scan.faults.gaps + scan.faults.clock_jumps, 0u);

  std::size_t compared = 0;
  std::size_t on_ball = 0;
  for (int row = 0; row < scan.cloud.grid.rows; ++row) {
    const hal::Timestamp t = scan.frames[static_cast<std::size_t>(row)].stamp;
    // The axis stops at motion_end: a kink linear interpolation cannot follow.
    if (t > motion_end - milliseconds(25)) continue;
    const sim::ProfileTruth truth =
        sim::cast_profile(caster, options.geometry.ranger, cell.T_scene_ranger(t));
    for (int k = 0; k < scan.cloud.grid.cols; ++k) {
      const std::int32_t i = scan.cloud.grid.at(row, k);
      ASSERT_EQ(i >= 0, !std::isnan(truth.x_mm[static_cast<std::size_t>(k)])) << row << " " << k;
      if (i < 0) continue;
      const Eigen::Vector3d& hit = truth.point_scene[static_cast<std::size_t>(k)];
      ASSERT_LT((scan.cloud.points[static_cast<std::size_t>(i)] - hit).norm(), 0.001)
          << "profile " << row << " point " << k;
      ++compared;
      on_ball += truth.object[static_cast<std::size_t>(k)] == 1;
    }
  }
  EXPECT_GT(compared, 10000u);
  EXPECT_GT(on_ball, 1000u);  // the moving object, not only the flat table, is checked
}

}  // namespace stripe_sim_test
}  // namespace rangefit::fusion
