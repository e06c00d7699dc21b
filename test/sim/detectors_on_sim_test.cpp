// The detectors of thesis ch. 4 and 5 find their targets in the simulator's scans, fused from the
// raw HAL streams exactly as on the cell.
#include <gtest/gtest.h>

#include <cmath>

#include "detect/bore/bore_detector.hpp"
#include "detect/object/object_detector.hpp"
#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"
#include "sim/css_simulator.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"
#include "sim_test_scans.hpp"
#include "sim_test_scenes.hpp"

namespace rangefit::sim {
namespace detectors_on_sim_test {

TEST(DetectorsOnSimulatedScans, BoreDetectorFindsTheBoreInANoisyCssScan) {
  const Scene scene = testing::css_bore_scene(BoreKind::kStraight, 12.0);
  const RayCaster caster(scene);
  SimClock clock;
  CssScanOptions o;
  o.seed = 11;
  o.css_faults.range_noise_sigma_mm = 0.06;  // thesis 4.2.1
  CssRig rig(scene, caster, o, clock);
  std::vector<hal::CssRevolution> revs;
  std::vector<hal::JointSample> joints;
  ASSERT_TRUE(rig.css().start());
  ASSERT_TRUE(rig.joint().start());
  while (clock.now() < rig.scan_end() + std::chrono::milliseconds(300)) {
    rig.css().read(revs, std::chrono::milliseconds(100));
    rig.joint().read(joints, std::chrono::milliseconds(0));
  }
  fusion::CssFusionConfig config;
  config.geometry = o.geometry;
  const fusion::FusedScan scan = fusion::fuse_css_scan(config, revs, joints);
  ASSERT_FALSE(scan.bad) << scan.reason;
  ASSERT_GT(scan.cloud.size(), 50000u);

  const BoreTruth& truth = scene.bores.at(0);
  BorePrior prior;
  prior.entrance = truth.opening_mm + Eigen::Vector3d(0.8, -0.5, 0.0);  // CAD vs. real part
  prior.axis = -truth.axis;
  prior.radius = 0.5 * truth.diameter_mm;
  const BoreResult r = detect_bore(scan.cloud, prior);
  ASSERT_TRUE(r.found);
  EXPECT_LT((r.entrance - truth.opening_mm).norm(), 0.3);  // thesis: +-0.3 mm
  EXPECT_LT(std::acos(std::min(1.0, std::abs(r.axis.dot(truth.axis)))) * 180.0 / 3.14159265, 0.5);
  EXPECT_NEAR(r.radius, 6.0, 0.1);
}

TEST(DetectorsOnSimulatedScans, ObjectDetectorFindsTheSphereInAStripeCellScan) {
  const Scene scene =
      load_scene(std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/table_top_fig5_18.toml");
  const RayCaster caster(scene);
  const fusion::FusedScan scan = testing::stripe_cell_scan(scene, caster, 5);
  ASSERT_FALSE(scan.bad) << scan.reason;
  const auto points = testing::thinned(scan, scene.mounts.T_scene_stripe);
  ASSERT_GT(points.size(), 50000u);
  ObjectModel sphere{"sphere", {{"sphere", Superquadric{50, 50, 50, 1.0, 1.0, 0.0, 0.0}}}, {}};
  ObjectDetectOptions opt;
  opt.seed = 3;
  const ObjectDetectResult r = detect_object(sphere, points, opt);
  ASSERT_TRUE(r.found()) << to_string(r.reason);
  // Thesis 5.2.2: a true positive lies within 3 mm of the ground truth (table 5.3).
  EXPECT_LT((r.instances[0].parts[0].center() - Eigen::Vector3d(160.0, 65.0, 50.0)).norm(), 3.0);
}

}  // namespace detectors_on_sim_test
}  // namespace rangefit::sim
