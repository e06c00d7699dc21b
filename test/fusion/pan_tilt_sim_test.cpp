// The pan-tilt assembler against the simulated mobile scanning head (sim/pan_tilt_head.hpp):
// the first second of a 10 deg/s sweep over a wall with a ball in front of it; every fused point
// is compared with the exact ray-cast hit of its fan ray at the profile's exposure centre.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "fusion/profile_assembler.hpp"
#include "sim/pan_tilt_head.hpp"
#include "sim/ranger_simulator.hpp"
#include "sim/sim_clock.hpp"

namespace rangefit::fusion {
namespace pan_tilt_sim_test {

using std::chrono::milliseconds;

TEST(PanTiltAssemblerOnSimulator, EveryFusedPointIsWithinAMicrometreOfTheRayCastHit) {
  sim::Scene scene;  // scene frame = eq. 5.7 world (mounts identity)
  Eigen::Isometry3d wall = Eigen::Isometry3d::Identity();
  wall.translation() = Eigen::Vector3d(0.0, 0.0, 1200.0);
  scene.objects.push_back({"wall", sim::PlaneShape{3000.0, 3000.0}, wall});
  Eigen::Isometry3d ball = Eigen::Isometry3d::Identity();
  ball.translation() = Eigen::Vector3d(0.0, 380.0, 1000.0);
  scene.objects.push_back({"ball", sim::SphereShape{100.0}, ball});
  const sim::RayCaster caster(scene);
  sim::SimClock clock;
  sim::PanTiltOptions options;
  options.quantise = false;
  options.tilt_rad = 0.05;
  options.geometry.t_s_mm = {0.0, 30.0, 60.0};
  sim::PanTiltHead head(scene, caster, options, clock);
  PanTiltFusionConfig config;
  config.geometry = options.geometry;
  PanTiltAssembler assembler(config);

  ASSERT_TRUE(head.ranger().start());
  ASSERT_TRUE(head.angles().start());
  const hal::Timestamp stop = head.sweep_start() + std::chrono::seconds(1);
  std::vector<hal::RangerProfile> profiles;
  std::vector<hal::PanTiltSample> angles;
  while (clock.now() < stop) {
    profiles.clear();
    angles.clear();
    head.ranger().read(profiles, milliseconds(500));
    head.angles().read(angles, milliseconds(0));
    for (const auto& a : angles) assembler.add_pan_tilt(a);
    for (const auto& p : profiles) assembler.add_profile(p);
  }
  const FusedScan scan = assembler.finish();
  EXPECT_EQ(scan.faults.out_of_order + scan.faults.gaps + scan.faults.clock_jumps, 0u);

  std::size_t compared = 0;
  std::size_t on_ball = 0;
  for (int row = 0; row < scan.cloud.grid.rows; ++row) {
    const hal::Timestamp t = scan.frames[static_cast<std::size_t>(row)].stamp;
    if (t < head.sweep_start() + milliseconds(15)) continue;  // the sweep's start is a kink
    const sim::ProfileTruth truth =
        sim::cast_profile(caster, options.geometry.ranger, head.T_scene_ranger(t));
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
  EXPECT_GT(compared, 20000u);
  EXPECT_GT(on_ball, 500u);
}

}  // namespace pan_tilt_sim_test
}  // namespace rangefit::fusion
