// The CSS assembler against the simulator's ray-cast ground truth (sim/css_simulator.hpp): the
// two streams are read as the daemon reads them, fused as they arrive, and every fused point is
// compared with the exact hit of its beam.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "fusion/css_assembler.hpp"
#include "sim/css_simulator.hpp"
#include "sim/ray_caster.hpp"
#include "sim/sim_clock.hpp"

namespace rangefit::fusion {
namespace css_sim_test {

using std::chrono::milliseconds;
constexpr int kCols = hal::CssRevolution::kSamples;

// A floor facing the sensor at its standoff (world z = R), a sphere and a box on it.
sim::Scene scene() {
  const hal::CssGeometry g;
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  base.translation() = Eigen::Vector3d(0.0, 0.0, g.pivot_radius_mm);
  sim::Scene s;
  s.objects.push_back({"floor", sim::PlaneShape{300.0, 300.0}, base});
  Eigen::Isometry3d ball = base;
  ball.translation() += Eigen::Vector3d(10.0, -3.0, 0.0);
  s.objects.push_back({"ball", sim::SphereShape{5.0}, ball});
  Eigen::Isometry3d box = base;
  box.translation() += Eigen::Vector3d(-10.0, 4.0, 4.0);
  s.objects.push_back({"block", sim::BoxShape{Eigen::Vector3d(8.0, 10.0, 8.0)}, box});
  return s;
}

TEST(CssAssemblerOnSimulator, EveryFusedPointIsWithinAMicrometreOfTheRayCastHit) {
  const sim::Scene sc = scene();
  const sim::RayCaster caster(sc);
  sim::SimClock clock;
  sim::CssScanOptions options;
  options.deflection_rad = 0.5 * std::numbers::pi / 180.0;  // 5 mm of path, ~17 revolutions
  sim::CssRig rig(sc, caster, options, clock);
  CssFusionConfig config;
  config.geometry = options.geometry;
  config.deflection_rad = options.deflection_rad;
  CssAssembler assembler(config);

  ASSERT_TRUE(rig.css().start());
  ASSERT_TRUE(rig.joint().start());
  std::vector<hal::CssRevolution> revs;
  std::vector<hal::JointSample> joints;
  while (clock.now() < rig.scan_end() + milliseconds(20)) {
    revs.clear();
    joints.clear();
    rig.css().read(revs, milliseconds(500));
    rig.joint().read(joints, milliseconds(0));
    for (const auto& j : joints) assembler.add_joint(j);
    for (const auto& r : revs) assembler.add_revolution(r);
  }
  const FusedScan scan = assembler.finish();
  EXPECT_EQ(scan.faults.total(), 0u) << scan.reason;

  std::size_t compared = 0;
  for (int row = 0; row < scan.cloud.grid.rows; ++row) {
    const FrameInfo& frame = scan.frames[static_cast<std::size_t>(row)];
    // The joint stops at +delta; beyond that the path has a kink the stream cannot show.
    if (frame.stamp + rig.revolution_stamp(1) - rig.revolution_stamp(0) > rig.scan_end()) continue;
    const sim::CssRevolutionTruth truth = rig.cast_revolution(frame.sequence);
    for (int i = 0; i < kCols; ++i) {
      const std::int32_t k = scan.cloud.grid.at(row, i);
      ASSERT_EQ(k >= 0, !std::isnan(truth.range_mm[i])) << "row " << row << " sample " << i;
      if (k < 0) continue;
      const Eigen::Vector3d p =
          sc.mounts.T_scene_css * scan.cloud.points[static_cast<std::size_t>(k)];
      ASSERT_LT((p - truth.point_scene[i]).norm(), 0.001) << "row " << row << " sample " << i;
      ++compared;
    }
  }
  EXPECT_GT(compared, 5000u);
}

}  // namespace css_sim_test
}  // namespace rangefit::fusion
