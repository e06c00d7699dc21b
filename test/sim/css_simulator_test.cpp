#include "sim/css_simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "sim/analytic_shapes.hpp"
#include "sim/sim_clock.hpp"
#include "sim_test_scenes.hpp"

namespace rangefit::sim {
namespace {

constexpr int kN = hal::CssRevolution::kSamples;

CssScanOptions short_scan() {
  CssScanOptions o;
  o.deflection_rad = 0.5 * std::numbers::pi / 180.0;  // 5 mm of path: ~17 revolutions
  return o;
}

std::vector<hal::CssRevolution> read_all(CssRig& rig, SimClock& clock) {
  std::vector<hal::CssRevolution> out;
  EXPECT_TRUE(rig.css().start());
  while (clock.now() < rig.scan_end()) rig.css().read(out, std::chrono::milliseconds(500));
  return out;
}

TEST(CssSimulator, AnalyticSceneScanLandsOnTheTrueSurfaces) {
  const Scene scene = testing::css_analytic_scene();
  const RayCaster caster(scene);
  SimClock clock;
  const CssRig rig(scene, caster, CssScanOptions{}, clock);
  std::set<int> objects_seen;
  int valid = 0;
  for (std::uint64_t k = 0; k < rig.revolutions_in_scan(); ++k) {
    const CssRevolutionTruth t = rig.cast_revolution(k);
    for (int i = 0; i < kN; ++i) {
      if (std::isnan(t.range_mm[i])) continue;
      ++valid;
      const SceneObject& obj = scene.objects[t.object[i]];
      objects_seen.insert(t.object[i]);
      ASSERT_LT(surface_distance(obj.shape, obj.T_world_object, t.point_scene[i]), 1e-6)
          << obj.name << " revolution " << k << " sample " << i;
      // The point also lies on the beam at the reported range (eq. 4.17 model).
      const auto& g = rig.options().geometry;
      const Eigen::Vector3d p =
          g.T_world_css(t.omega_rad[i]) * g.sensor_point(g.beam_angle(i, kN), t.range_mm[i]);
      ASSERT_LT((p - t.point_scene[i]).norm(), 1e-9);
    }
  }
  EXPECT_GT(valid, 5000);
  EXPECT_EQ(objects_seen.size(), scene.objects.size()) << "every object is hit";
}

TEST(CssSimulator, StreamRangesMatchTheExactRangesWithoutNoise) {
  const Scene scene = testing::css_analytic_scene();
  const RayCaster caster(scene);
  SimClock clock;
  CssRig rig(scene, caster, short_scan(), clock);
  const auto revs = read_all(rig, clock);
  ASSERT_GE(revs.size(), rig.revolutions_in_scan() - 1);
  for (const auto& rev : revs) {
    const CssRevolutionTruth t = rig.cast_revolution(rev.sequence);
    EXPECT_EQ(rev.stamp, rig.revolution_stamp(rev.sequence));
    EXPECT_EQ(rev.stamp.count() % 1000, 0) << "stamps have microsecond resolution";
    for (int i = 0; i < kN; ++i) {
      if (std::isnan(t.range_mm[i])) {
        EXPECT_TRUE(std::isnan(rev.range_mm[i]));
      } else {
        EXPECT_NEAR(rev.range_mm[i], t.range_mm[i], 1e-4);  // float quantisation only
      }
    }
  }
}

TEST(CssSimulator, ShadowedSamplesAreAbsentAsABruteForceCheckPredicts) {
  const Scene scene = testing::css_analytic_scene();
  const RayCaster caster(scene);
  SimClock clock;
  const CssRig rig(scene, caster, short_scan(), clock);
  const auto& g = rig.options().geometry;
  int shadowed = 0;
  for (std::uint64_t k = 0; k < rig.revolutions_in_scan(); k += 4) {
    const CssRevolutionTruth t = rig.cast_revolution(k);
    for (int i = 0; i < kN; ++i) {
      const Eigen::Isometry3d T = g.T_world_css(t.omega_rad[i]);
      const Eigen::Vector3d o = T * g.laser_point();
      const Ray beam{o, T.linear() * g.beam_direction(g.beam_angle(i, kN)), 0.0, g.max_range_mm};
      const Hit h = caster.cast_brute_force(beam);
      bool expect_valid = h.valid && h.t >= g.min_range_mm;
      if (expect_valid) {
        const Eigen::Vector3d to_ccd = T * g.ccd_point() - h.point;
        const Hit back =
            caster.cast_brute_force(Ray{h.point, to_ccd.normalized(), 1e-3, to_ccd.norm() - 1e-3});
        if (back.valid) {
          expect_valid = false;
          ++shadowed;
        }
      }
      ASSERT_EQ(!std::isnan(t.range_mm[i]), expect_valid) << "revolution " << k << " sample " << i;
    }
  }
  EXPECT_GT(shadowed, 50) << "the scene must cast camera shadows for the test to mean anything";
}

// Thesis 1.1.1 / 4.2.4: laser and CCD look into a bore from one side, so a scan shows only a
// fragment of the wall (the thesis quotes at most ~120 deg; this model of a 12 mm bore in a
// 20 mm plate gives ~160 deg, counting every 1-deg sector holding any point 1.5 mm below the rim).
TEST(CssSimulator, BoreScanShowsLessThanHalfOfTheWall) {
  const Scene scene = testing::css_bore_scene(BoreKind::kStraight, 12.0);
  const RayCaster caster(scene);
  SimClock clock;
  CssScanOptions o;  // the full +-5 deg scan
  const CssRig rig(scene, caster, o, clock);
  const Eigen::Isometry3d T_plate_scene = scene.objects[0].T_world_object.inverse();
  std::set<int> wall_degrees;
  for (std::uint64_t k = 0; k < rig.revolutions_in_scan(); ++k) {
    const CssRevolutionTruth t = rig.cast_revolution(k);
    for (int i = 0; i < kN; ++i) {
      if (std::isnan(t.range_mm[i])) continue;
      const Eigen::Vector3d p = T_plate_scene * t.point_scene[i];
      if (p.z() > -1.5) continue;  // top face and the rim's edge
      const double deg = std::atan2(p.y(), p.x()) * 180.0 / std::numbers::pi;
      wall_degrees.insert(static_cast<int>(std::floor(deg)));
    }
  }
  EXPECT_GT(wall_degrees.size(), 30u) << "some wall is visible";
  EXPECT_LT(wall_degrees.size(), 180u) << "less than half of the wall";
}

TEST(CssSimulator, EmptySceneGivesRevolutionsWithoutReturns) {
  const Scene scene;
  const RayCaster caster(scene);
  SimClock clock;
  CssRig rig(scene, caster, short_scan(), clock);
  const auto revs = read_all(rig, clock);
  ASSERT_FALSE(revs.empty());
  for (const auto& rev : revs) {
    for (float r : rev.range_mm) ASSERT_TRUE(std::isnan(r));
  }
  EXPECT_EQ(rig.css().health().counters.samples, revs.size());
}

TEST(CssSimulator, JointStreamFollowsTheScanPathAtTheTcpSpeed) {
  const Scene scene;
  const RayCaster caster(scene);
  SimClock clock;
  CssRig rig(scene, caster, short_scan(), clock);
  ASSERT_TRUE(rig.joint().start());
  std::vector<hal::JointSample> samples;
  while (clock.now() < rig.scan_end()) rig.joint().read(samples, std::chrono::milliseconds(100));
  ASSERT_GT(samples.size(), 100u);
  const double delta = rig.options().deflection_rad;
  EXPECT_NEAR(samples.front().angle_rad, -delta, 1e-3);
  EXPECT_NEAR(samples.back().angle_rad, delta, 1e-3);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    ASSERT_GT(samples[i].stamp, samples[i - 1].stamp);
    ASSERT_GE(samples[i].angle_rad, samples[i - 1].angle_rad);
    EXPECT_EQ(samples[i].joint, 6);
  }
  // v = d omega / dt * R (eq. 4.21).
  EXPECT_NEAR(samples[10].velocity_rad_s * rig.options().geometry.pivot_radius_mm, 2.0, 1e-9);
}

}  // namespace
}  // namespace rangefit::sim
