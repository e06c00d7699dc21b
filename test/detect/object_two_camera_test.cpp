// Object detection on a stripe ranger with a camera on each side of its laser plane: a point the
// laser lit is measured when either camera sees it, so a part that a tall wall hides from one
// camera is still scanned by the other. The detector, told both cameras, judges the part on
// what either could have seen.
#include <gtest/gtest.h>

#include <string>

#include "detect/object/object_detector.hpp"
#include "sim/scene_objects.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/detect/stripe_scan_fixture.hpp"
#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace object_two_camera_test {

// The box of table 5.2 standing, and a wall 150 mm high 10 mm beyond its +y face: the +y camera
// (45 degrees off the vertical laser plane) sees next to nothing of the box past the wall.
sim::VariedScene walled_box(bool two_cameras) {
  Superquadric wall = sim::box_model();
  wall.a1 = 70.0, wall.a2 = 5.0, wall.a3 = 75.0;
  std::vector<sim::ScenePart> parts = {
      test::placed("box", sim::box_model(), {0.0, 0.0, 50.0}, Eigen::Vector3d::UnitZ()),
      test::placed("wall", wall, {0.0, 40.0, 75.0}, Eigen::Vector3d::UnitZ())};
  sim::VariedScene::Factors f;
  f.scan.triangulation_deg = 45.0;
  f.scan.camera_side = +1;
  f.scan.two_cameras = two_cameras;
  f.scan.laser_height_mm = 600.0;
  f.scan.step_mm = 1.0;
  f.scan.noise_mm = 0.1;
  f.scan.max_points = 60000;
  const Eigen::AlignedBox3d cover(Eigen::Vector3d(-90, -90, 0), Eigen::Vector3d(90, 90, 160));
  return sim::scan_varied_scene(std::move(parts), {0}, sim::single("box", sim::box_model()),
                                sim::make_sweep(f.scan, cover), f, 3);
}

TEST(ObjectTwoCameras, TheSecondCameraSitsAcrossTheLaserPlaneAndEitherMeasures) {
  const sim::VariedScene one = walled_box(false), two = walled_box(true);
  ASSERT_TRUE(valid(two.view));
  // Mirrored across the laser plane (vertical, normal y) at the same angle.
  EXPECT_NEAR(two.view.second_camera_offset.y(), -two.view.camera_offset.y(), 1e-9);
  EXPECT_NEAR(two.view.second_camera_offset.z(), two.view.camera_offset.z(), 1e-9);
  EXPECT_EQ(sensor_eyes(two.view, two.cloud.points[0]).count, 3);
  EXPECT_EQ(sensor_eyes(one.view, one.cloud.points[0]).count, 2);
  // The box's -y face and the table in the wall's shadow are scanned only with two cameras.
  const auto on_box = [](const sim::VariedScene& s) {
    int n = 0;
    for (std::int32_t l : s.label) n += l == 0;
    return n;
  };
  EXPECT_GT(on_box(two), 3 * on_box(one)) << on_box(two) << " against " << on_box(one);
}

TEST(ObjectTwoCameras, APartWalledOffFromOneCameraIsJudgedOnWhatTheOtherSaw) {
  const sim::VariedScene s = walled_box(true);
  const ObjectDetectResult r = test::detect_in(s, 5);
  ASSERT_TRUE(r.found()) << test::describe_rejections(r);
  EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part, s.parts[0], true));
  EXPECT_GT(r.instances[0].parts[0].scores.coverage, 0.8);

  // Told only the walled-off camera, the detector cannot tell that the camera's lines of sight
  // through the wall's unlit faces (the laser's shadow) were clear; the scan points behind the
  // wall say they were, so the box is still found, but its bare samples there are no evidence
  // and it is judged on fewer of them.
  ObjectDetectOptions o;
  o.sensor = s.view;
  o.sensor.second_camera_offset.setZero();
  o.seed = 5;
  const ObjectDetectResult r1 = detect_object(s.model, s.cloud.points, o);
  ASSERT_TRUE(r1.found()) << test::describe_rejections(r1);
  EXPECT_TRUE(test::true_positive(r1.instances[0].parts[0].T_world_part, s.parts[0], true));
  EXPECT_LT(r1.instances[0].parts[0].scores.measurable, r.instances[0].parts[0].scores.measurable);
}

// Varied scenes with two cameras: the targets of a few tuning seeds are found where they stand.
TEST(ObjectTwoCameras, FindsVariedTargetsUnderBothCameras) {
  for (sim::VariedTarget target : {sim::VariedTarget::kBox, sim::VariedTarget::kCylinder}) {
    sim::VariedSceneOptions so;
    so.target = target;
    so.two_camera_probability = 1.0;
    so.occlusion_max = 0.3;
    for (std::uint64_t seed : {2, 3}) {
      const sim::VariedScene s = sim::make_varied_scene(so, seed);
      ASSERT_TRUE(s.factors.scan.two_cameras);
      const ObjectDetectResult r = test::detect_in(s, seed);
      ASSERT_TRUE(r.found()) << sim::to_string(target) << " seed " << seed << ": "
                             << test::describe_rejections(r);
      EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part,
                                      s.parts[static_cast<std::size_t>(s.target_parts[0])], true))
          << sim::to_string(target) << " seed " << seed;
    }
  }
}

}  // namespace object_two_camera_test
}  // namespace rangefit
