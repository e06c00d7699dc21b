#include "detect/object/object_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace object_detector_test {

using test::Scene;

// Reduced resolution (~50,000 points) and a few seeds keep the suite fast; the benchmark runs
// the full 140,000-point scene over 100 seeds.
constexpr double kScale = 0.6;
#if defined(__SANITIZE_ADDRESS__)
constexpr int kSeeds = 2;  // ASan+UBSan runs ~10x slower; the Release build runs them all
#else
constexpr int kSeeds = 5;
#endif

const Scene& fig_scene() {
  static const Scene s = test::fig_5_18_scene(0.0, 1, kScale);
  return s;
}

const Scene& mallet_scene() {
  static const Scene s = test::mallet_scene(0.0, 1, kScale);
  return s;
}

ObjectDetectOptions options_for(const Scene& s, std::uint64_t seed) {
  ObjectDetectOptions o;
  o.viewpoint = s.eye;
  o.seed = seed;
  return o;
}

int true_positives(const ObjectModel& model, const Scene& scene, std::size_t truth, bool axis) {
  int tp = 0;
  for (int s = 1; s <= kSeeds; ++s) {
    const ObjectDetectResult r = detect_object(model, scene.rendered.cloud.points,
                                               options_for(scene, static_cast<std::uint64_t>(s)));
    if (r.found() &&
        test::true_positive(r.instances[0].parts[0].T_world_part, scene.parts[truth], axis)) {
      ++tp;
    }
  }
  return tp;
}

TEST(ObjectDetector, FindsTheFigure518CylinderBoxAndSphereForEverySeed) {
  EXPECT_EQ(true_positives(test::single("cylinder", test::cylinder_model()), fig_scene(), 0, true),
            kSeeds);
  EXPECT_EQ(true_positives(test::single("box", test::box_model()), fig_scene(), 1, true), kSeeds);
  EXPECT_EQ(true_positives(test::single("sphere", test::sphere_model()), fig_scene(), 2, false),
            kSeeds);
}

// Found is not enough for a grasp: on this noise-free scan every pose is within a millimetre
// and a degree (the narrowing refinement band keeps neighbouring objects out of the fit; with
// the first, wide band the sphere sat 2.3 mm off and the box 1.7 degrees).
TEST(ObjectDetector, PosesAreWithinAMillimetreAndADegree) {
  const Superquadric models[] = {test::cylinder_model(), test::box_model(), test::sphere_model(),
                                 test::cone_model()};
  for (std::size_t i = 0; i < 4; ++i) {
    const ObjectDetectResult r =
        detect_object(test::single("part", models[i]), fig_scene().rendered.cloud.points,
                      options_for(fig_scene(), 1));
    ASSERT_TRUE(r.found()) << i;
    const test::PoseError e =
        test::pose_error(r.instances[0].parts[0].T_world_part, fig_scene().parts[i]);
    EXPECT_LT(e.centre_mm, 1.0) << i;
    if (i != 2) {  // the sphere has no axis
      EXPECT_GT(e.axis_cos, std::cos(1.0 * std::numbers::pi / 180.0)) << i;
    }
  }
}

TEST(ObjectDetector, FindsTheTaperedConeForEverySeed) {
  EXPECT_EQ(true_positives(test::single("cone", test::cone_model()), fig_scene(), 3, true), kSeeds);
}

// The link vote picks the real mallet (head and shaft) over the look-alikes, and the joint
// refinement keeps the head's points out of the shaft's fit: both parts are true positives
// (before it, the shaft centre sat ~13 mm along its axis towards the head).
TEST(ObjectDetector, FindsBothPartsOfTheLinkedMalletAmongLookAlikes) {
  const Scene& s = mallet_scene();
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const ObjectDetectResult r = detect_object(test::mallet_model(), s.rendered.cloud.points,
                                               options_for(s, static_cast<std::uint64_t>(seed)));
    ASSERT_TRUE(r.found()) << to_string(r.reason);
    ASSERT_EQ(r.instances[0].parts.size(), 2u);
    EXPECT_EQ(r.instances[0].parts[1].name, "shaft");
    EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part, s.parts[0])) << seed;
    EXPECT_TRUE(test::true_positive(r.instances[0].parts[1].T_world_part, s.parts[1])) << seed;
    EXPECT_LT(r.instances[0].link_distance_error_mm[0], 3.0);
  }
}

// The daemon's demo asks for models that are not on the table: the detector must say so rather
// than return its least bad misfit (a mallet head on the cylinder without its shaft, a rod along
// an edge, a small ball in a corner, a flat 80 x 80 x 20 mm slab laid against a face of the
// 50 x 50 x 100 mm box, which covers 70% of what it shows the sensor but claims surface where
// the sensor saw the table).
TEST(ObjectDetector, ReportsNotFoundForObjectsThatAreNotInTheScene) {
  const Scene& s = fig_scene();
  const ObjectModel absent[] = {test::mallet_model(),
                                test::single("rod", {12, 10, 120, 0.1, 1.0, 0, 0}),
                                test::single("ball", {20, 20, 20, 1.0, 1.0, 0, 0}),
                                test::single("slab", {40, 40, 10, 0.1, 0.1, 0, 0})};
  for (const ObjectModel& model : absent) {
    for (int seed = 1; seed <= 2; ++seed) {
      const ObjectDetectResult r = detect_object(model, s.rendered.cloud.points,
                                                 options_for(s, static_cast<std::uint64_t>(seed)));
      EXPECT_FALSE(r.found()) << model.name << " seed " << seed << " at "
                              << r.instances[0].parts[0].center().transpose() << " coverage "
                              << r.instances[0].parts[0].scores.coverage << " seen through "
                              << r.instances[0].parts[0].scores.seen_through;
      EXPECT_TRUE(r.reason == DetectReason::kNotConfirmed || r.reason == DetectReason::kNotLinked)
          << model.name << ": " << to_string(r.reason);
    }
  }
  // Without the viewpoint the visible side is inferred from the points: still not found.
  ObjectDetectOptions o = options_for(s, 1);
  o.viewpoint.reset();
  EXPECT_FALSE(detect_object(absent[1], s.rendered.cloud.points, o).found());
  EXPECT_FALSE(detect_object(absent[2], s.rendered.cloud.points, o).found());
  EXPECT_TRUE(
      detect_object(test::single("box", test::box_model()), s.rendered.cloud.points, o).found());
}

// The fig. 5.18 cone, partly in the sphere's shadow, passes every check at its first hypotheses
// with all its measurable surface covered; waiting for a third agreeing hypothesis only cost
// time. Fewer hypotheses over the seeds, and the same cone found each time.
TEST(ObjectDetector, AFullyCoveredLeaderEndsTheSearchAfterTwoAgreeingHypotheses) {
  const ObjectModel cone = test::single("cone", test::cone_model());
  int waited = 0, covered = 0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    ObjectDetectOptions o = options_for(fig_scene(), static_cast<std::uint64_t>(seed));
    for (const int needed : {3, 2}) {
      o.confirmations_covered = needed;
      const ObjectDetectResult r = detect_object(cone, fig_scene().rendered.cloud.points, o);
      ASSERT_TRUE(r.found()) << "seed " << seed << ": " << to_string(r.reason);
      EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part, fig_scene().parts[3]))
          << "seed " << seed;
      (needed == 3 ? waited : covered) += r.hypotheses_evaluated;
    }
  }
  EXPECT_LT(covered, waited);
}

TEST(ObjectDetector, ReportsTheRemovedTablePlane) {
  const ObjectDetectResult r =
      detect_object(test::single("sphere", test::sphere_model()), fig_scene().rendered.cloud.points,
                    options_for(fig_scene(), 1));
  ASSERT_TRUE(r.plane.removed());
  EXPECT_GT(std::abs(r.plane.plane.normal.z()), 0.999);
  EXPECT_GT(r.time.total_ms, 0.0);
  EXPECT_GE(r.hypotheses_evaluated, 1);
}

TEST(ObjectDetector, ResultDependsOnlyOnTheSeedNotOnThreads) {
  const Scene& s = fig_scene();
  ObjectDetectOptions o = options_for(s, 7);
  o.threads = 1;
  const ObjectDetectResult a =
      detect_object(test::single("box", test::box_model()), s.rendered.cloud.points, o);
  o.threads = 3;
  const ObjectDetectResult b =
      detect_object(test::single("box", test::box_model()), s.rendered.cloud.points, o);
  ASSERT_TRUE(a.found() && b.found());
  EXPECT_EQ(a.hypotheses_evaluated, b.hypotheses_evaluated);
  EXPECT_TRUE(
      a.instances[0].parts[0].T_world_part.isApprox(b.instances[0].parts[0].T_world_part, 0.0));
}

TEST(ObjectDetector, ReturnsSeveralInstancesWithoutDuplicates) {
  // Three equal cylinders standing and lying on the table: asked for three, each is found once.
  std::vector<sim::ScenePart> parts = {
      {"a", test::cylinder_model(), test::pose_from_axis({40, 60, 50}, {0, 0, 1})},
      {"b", test::cylinder_model(), test::pose_from_axis({200, 40, 30}, {1, 0.3, 0})},
      {"c", test::cylinder_model(), test::pose_from_axis({150, 200, 50}, {0.2, 0, 1})}};
  sim::SceneView view = test::table_view();
  view.width = 264;
  view.height = 198;
  const Scene s = test::render(parts, view);
  const ObjectModel model = test::single("cylinder", test::cylinder_model());
  ObjectDetectOptions o = options_for(s, 3);
  o.instances = 3;
  o.early_stop = false;
  const ObjectDetectResult r = detect_object(model, s.rendered.cloud.points, o);
  ASSERT_EQ(r.instances.size(), 3u);
  std::vector<int> hits(parts.size(), 0);
  for (const DetectedInstance& inst : r.instances) {
    for (std::size_t k = 0; k < parts.size(); ++k) {
      if (test::true_positive(inst.parts[0].T_world_part, parts[k])) ++hits[k];
    }
  }
  EXPECT_EQ(hits, std::vector<int>({1, 1, 1}));
  // Asked for more than there are: still no duplicate, and the extra one is not invented.
  o.instances = 5;
  const ObjectDetectResult more = detect_object(model, s.rendered.cloud.points, o);
  EXPECT_EQ(more.instances.size(), 3u);
}

TEST(ObjectDetector, EmptyCloudInvalidModelAndOptionsAreReasonsNotCrashes) {
  const ObjectModel sphere = test::single("sphere", test::sphere_model());
  EXPECT_EQ(detect_object(sphere, {}).reason, DetectReason::kEmptyCloud);
  std::vector<Eigen::Vector3d> nan_points(10, Eigen::Vector3d(NAN, 1, 1));
  EXPECT_EQ(detect_object(sphere, nan_points).reason, DetectReason::kEmptyCloud);
  ObjectModel bad = sphere;
  bad.parts[0].shape.a1 = -1.0;
  EXPECT_EQ(detect_object(bad, fig_scene().rendered.cloud.points).reason,
            DetectReason::kInvalidModel);
  ObjectModel bad_link = test::mallet_model();
  bad_link.links[0].second = 5;
  EXPECT_EQ(detect_object(bad_link, fig_scene().rendered.cloud.points).reason,
            DetectReason::kInvalidModel);
  EXPECT_EQ(detect_object(ObjectModel{}, fig_scene().rendered.cloud.points).reason,
            DetectReason::kInvalidModel);
  ObjectDetectOptions o;
  o.hypotheses = 0;
  EXPECT_EQ(detect_object(sphere, fig_scene().rendered.cloud.points, o).reason,
            DetectReason::kInvalidOptions);
  ObjectDetectOptions no_batch;
  no_batch.compound_batch = 0;  // would never end the search
  EXPECT_EQ(detect_object(test::mallet_model(), fig_scene().rendered.cloud.points, no_batch).reason,
            DetectReason::kInvalidOptions);
  // A cloud far too sparse for any patch: searched, nothing found, no crash.
  std::vector<Eigen::Vector3d> sparse = {{0, 0, 0}, {500, 0, 0}, {0, 500, 0}, {0, 0, 500}};
  const ObjectDetectResult r = detect_object(sphere, sparse);
  EXPECT_FALSE(r.found());
  EXPECT_EQ(r.reason, DetectReason::kNoHypothesis);
}

}  // namespace object_detector_test
}  // namespace rangefit
