#include "detect/object_detector.hpp"

#include <gtest/gtest.h>

#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace {

using test::Scene;

// Reduced resolution (~50,000 points) and a few seeds keep the suite fast; the benchmark runs
// the full 140,000-point scene over 100 seeds.
constexpr double kScale = 0.6;
constexpr int kSeeds = 5;

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

TEST(ObjectDetector, FindsTheTaperedConeForAlmostEverySeed) {
  EXPECT_GE(true_positives(test::single("cone", test::cone_model()), fig_scene(), 3, true),
            kSeeds - 1);
}

// The link vote picks the real mallet (head and shaft) over the look-alikes. Known limit, see
// the issue note: the shaft centre is biased ~13 mm along its axis towards the head (head points
// enter the shaft's trimmed refinement), the thesis's "false negative along the axis"; so the
// shaft is checked for axis and off-axis position only.
TEST(ObjectDetector, PicksTheLinkedMalletAmongLookAlikes) {
  const Scene& s = mallet_scene();
  const Eigen::Vector3d shaft_axis = s.parts[1].T_world_part.linear().col(2);
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const ObjectDetectResult r = detect_object(test::mallet_model(), s.rendered.cloud.points,
                                               options_for(s, static_cast<std::uint64_t>(seed)));
    ASSERT_TRUE(r.found());
    ASSERT_EQ(r.instances[0].parts.size(), 2u);
    EXPECT_EQ(r.instances[0].parts[1].name, "shaft");
    EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part, s.parts[0])) << seed;
    const DetectedPart& shaft = r.instances[0].parts[1];
    const Eigen::Vector3d d = shaft.center() - s.parts[1].T_world_part.translation();
    EXPECT_LT((d - d.dot(shaft_axis) * shaft_axis).norm(), 3.0) << seed;
    EXPECT_LT(std::abs(d.dot(shaft_axis)), 20.0) << seed;
    EXPECT_GT(std::abs(shaft.z_axis().dot(shaft_axis)), std::cos(5.0 * std::numbers::pi / 180.0));
  }
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
  // Two equal spheres: both are found once each.
  std::vector<sim::ScenePart> parts = {
      {"a", test::sphere_model(), test::pose_from_axis({60, 100, 50}, {0, 0, 1})},
      {"b", test::sphere_model(), test::pose_from_axis({230, 120, 50}, {0, 0, 1})}};
  sim::SceneView view = test::table_view();
  view.width = 264;
  view.height = 198;
  const Scene s = test::render(parts, view);
  ObjectDetectOptions o = options_for(s, 3);
  o.instances = 2;
  o.hypotheses = 16;
  o.early_stop = false;
  const ObjectDetectResult r =
      detect_object(test::single("sphere", test::sphere_model()), s.rendered.cloud.points, o);
  ASSERT_EQ(r.instances.size(), 2u);
  const Eigen::Vector3d c0 = r.instances[0].parts[0].center(),
                        c1 = r.instances[1].parts[0].center();
  EXPECT_GT((c0 - c1).norm(), 100.0);
  for (const auto& inst : r.instances) {
    const Eigen::Vector3d c = inst.parts[0].center();
    EXPECT_LT(std::min((c - parts[0].T_world_part.translation()).norm(),
                       (c - parts[1].T_world_part.translation()).norm()),
              3.0);
  }
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
  // A cloud far too sparse for any patch: searched, nothing found, no crash.
  std::vector<Eigen::Vector3d> sparse = {{0, 0, 0}, {500, 0, 0}, {0, 500, 0}, {0, 0, 500}};
  const ObjectDetectResult r = detect_object(sphere, sparse);
  EXPECT_FALSE(r.found());
  EXPECT_EQ(r.reason, DetectReason::kNoHypothesis);
}

}  // namespace
}  // namespace rangefit
