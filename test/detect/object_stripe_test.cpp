// Object detection on laser-stripe scans of the thesis scenes (sim/varied_scene.hpp): the camera
// on either side of the laser plane at two triangulation angles, so every object throws laser
// and camera shadows on the table and on its neighbours. The detector is told the scan's
// SensorView, as the daemon and a scan saved by rangefit tell it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "detect/object/object_detector.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace object_stripe_test {

sim::ScanSetup setup(double triangulation_deg, int side, double noise_mm = 0.1) {
  sim::ScanSetup s;
  s.triangulation_deg = triangulation_deg;
  s.camera_side = side;
  s.laser_height_mm = 600.0;
  s.step_mm = 1.0;
  s.noise_mm = noise_mm;
  s.max_points = 70000;  // about half the benchmark's density keeps the suite fast
  return s;
}

ObjectDetectResult detect(const sim::VariedScene& s, std::uint64_t seed) {
  ObjectDetectOptions o;
  o.sensor = s.view;
  o.seed = seed;
  return detect_object(s.model, s.cloud.points, o);
}

bool found_truth(const ObjectDetectResult& r, const sim::VariedScene& s, bool axis = true) {
  if (!r.found()) return false;
  for (std::size_t p = 0; p < s.target_parts.size(); ++p) {
    if (!test::true_positive(r.instances[0].parts[p].T_world_part,
                             s.parts[static_cast<std::size_t>(s.target_parts[p])], axis)) {
      return false;
    }
  }
  return true;
}

std::string describe(const ObjectDetectResult& r) {
  std::string out = to_string(r.reason);
  for (const Rejection& x : r.rejections) {
    out += std::string("; ") + to_string(x.check) + " " + std::to_string(x.value) + " (limit " +
           std::to_string(x.limit) + ")";
  }
  return out;
}

struct Geometry {
  double triangulation_deg;
  int side;
};
#if defined(__SANITIZE_ADDRESS__)
// ASan+UBSan runs ~10x slower: one geometry per camera side; the Release build runs all four.
constexpr Geometry kGeometries[] = {{20.0, +1}, {45.0, -1}, {20.0, +1}, {45.0, -1}};
#else
constexpr Geometry kGeometries[] = {{20.0, +1}, {20.0, -1}, {45.0, +1}, {45.0, -1}};
#endif

// Fig. 5.18 under every geometry: the sphere, cylinder, box and cone, each a true positive.
TEST(ObjectStripe, FindsTheFigure518ObjectsWithTheCameraOnEitherSide) {
  const sim::VariedTarget targets[] = {sim::VariedTarget::kSphere, sim::VariedTarget::kCylinder,
                                       sim::VariedTarget::kBox, sim::VariedTarget::kCone};
  for (const Geometry& g : kGeometries) {
    for (sim::VariedTarget t : targets) {
      const sim::VariedScene s = sim::thesis_scene(t, setup(g.triangulation_deg, g.side), 1);
      const ObjectDetectResult r = detect(s, 1);
      EXPECT_TRUE(found_truth(r, s, t != sim::VariedTarget::kSphere))
          << sim::to_string(t) << " at " << g.triangulation_deg << " deg, side " << g.side << ": "
          << describe(r);
    }
  }
}

// What a found part reports (M, I, S of eq. 5.2-5.4) is measured at the pose it reports, also
// where that pose is the fit to its points' distances the confirmation moved it to (tuning seeds
// 4 and 9: before, such a part came back with M 0 and no surface points).
TEST(ObjectStripe, AFoundPartsScoresAreThoseOfThePoseItReports) {
  for (std::uint64_t seed : {4, 9}) {
    sim::VariedSceneOptions so;
    so.target = sim::VariedTarget::kBox;
    const sim::VariedScene s = sim::make_varied_scene(so, seed);
    const ObjectDetectResult r = detect(s, seed);
    ASSERT_TRUE(found_truth(r, s)) << "seed " << seed << ": " << describe(r);
    const DetectedPart& p = r.instances[0].parts[0];
    int near = 0;  // scan points on the reported surface (G within 10 % of 1)
    for (const Eigen::Vector3d& q : s.cloud.points) {
      near += std::abs(metric_world(s.model.parts[0].shape, p.T_world_part, q) - 1.0) < 0.1;
    }
    EXPECT_GT(p.scores.measure, 0.0) << "seed " << seed;
    EXPECT_LE(p.scores.measure, ObjectDetectOptions{}.max_measure) << "seed " << seed;
    EXPECT_NEAR(static_cast<double>(p.scores.surface), near, 0.05 * near) << "seed " << seed;
  }
}

// The mallet among a head-like drum, a shaft-like rod, a hammer and two occluding boxes.
TEST(ObjectStripe, FindsTheLinkedMalletAmongLookAlikes) {
  for (const Geometry& g : {kGeometries[1], kGeometries[2]}) {
    const sim::VariedScene s =
        sim::thesis_scene(sim::VariedTarget::kMallet, setup(g.triangulation_deg, g.side), 2);
    const ObjectDetectResult r = detect(s, 2);
    EXPECT_TRUE(found_truth(r, s))
        << g.triangulation_deg << " deg, side " << g.side << ": " << describe(r);
  }
}

// Fig. 5.28: the 50 mm sphere between spheres of 48 and 52 mm (4 % off), by its size, not by
// which of them shows more points.
TEST(ObjectStripe, TellsTheRightSphereFromLookAlikesFourPercentOff) {
  for (const Geometry& g : {kGeometries[0], kGeometries[3]}) {
    const sim::VariedScene s = sim::thesis_scene(sim::VariedTarget::kThreeSpheres,
                                                 setup(g.triangulation_deg, g.side, 0.3), 3);
    const ObjectDetectResult r = detect(s, 3);
    EXPECT_TRUE(found_truth(r, s, false))
        << g.triangulation_deg << " deg, side " << g.side << ": " << describe(r);
  }
}

// The mallet scene without the mallet: its look-alikes are not taken for it, and the answer
// says which check each candidate failed.
TEST(ObjectStripe, ReportsNotFoundWhenOnlyLookAlikesAreThere) {
  const sim::VariedScene s = sim::thesis_scene(sim::VariedTarget::kNone, setup(45.0, -1), 4);
  const ObjectDetectResult r = detect(s, 4);
  EXPECT_FALSE(r.found()) << r.instances[0].parts[0].center().transpose();
  EXPECT_NE(r.reason, DetectReason::kFound);
}

// Partly hidden: a seeded varied scene whose target is a quarter occluded by a wall is still
// found, and a one-part model that is not confirmed never says "parts not linked".
TEST(ObjectStripe, FindsAPartlyOccludedObjectAndGivesTrueReasons) {
  sim::VariedSceneOptions o;
  o.target = sim::VariedTarget::kSphere;
  o.occlusion_min = 0.2, o.occlusion_max = 0.3;
  o.noise_min_mm = 0.1, o.noise_max_mm = 0.1;
  o.step_min_mm = 1.0, o.step_max_mm = 1.0;
  o.max_points = 70000;
  o.clutter_min = 1, o.clutter_max = 2;
  const sim::VariedScene s = sim::make_varied_scene(o, 7);
  ASSERT_GT(s.factors.occlusion, 0.1);
  const ObjectDetectResult r = detect(s, 7);
  EXPECT_TRUE(found_truth(r, s, false)) << describe(r);
  ObjectModel absent = test::single("slab", {40, 40, 10, 0.1, 0.1, 0, 0});
  const ObjectDetectResult none = detect_object(absent, s.cloud.points, ObjectDetectOptions{});
  EXPECT_NE(none.reason, DetectReason::kNotLinked);
}

}  // namespace object_stripe_test
}  // namespace rangefit
