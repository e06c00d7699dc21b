// Two cameras of one laser sweep as one SensorView (with_second_camera): what it merges and what
// it refuses.
#include "detect/common/sensor_view.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace rangefit {
namespace sensor_view_test {

// A stripe cell's sweep: apex 600 mm up, vertical laser plane (normal y), moving along y over
// [-100, 100] mm, its camera `camera_y` mm off the plane level with the apex.
SensorView stripe(double camera_y, const Eigen::Vector3d& apex = {0.0, 0.0, 600.0}) {
  SensorView v;
  v.kind = SensorView::Kind::kLinearSweep;
  v.origin = apex;
  v.plane_normal = Eigen::Vector3d::UnitY();
  v.camera_offset = {0.0, camera_y, 0.0};
  v.direction = Eigen::Vector3d::UnitY();
  v.sweep_min = -100.0;
  v.sweep_max = 100.0;
  return v;
}

TEST(SensorViewCameras, TwoCamerasOfOneSweepMergeIntoThreeEyes) {
  // The second camera's own frame has its apex elsewhere in the same plane (a calibrated rig).
  const SensorView a = stripe(300.0), b = stripe(-280.0, {5.0, 0.0, 590.0});
  const std::optional<SensorView> both = with_second_camera(a, b);
  ASSERT_TRUE(both);
  EXPECT_TRUE(valid(*both));
  const Eigen::Vector3d p(10.0, 20.0, 0.0);
  const Eyes eyes = sensor_eyes(*both, p);
  ASSERT_EQ(eyes.count, 3);
  const Eyes first = sensor_eyes(a, p), second = sensor_eyes(b, p);
  EXPECT_LT((eyes.at[0] - first.at[0]).norm(), 1e-9);   // the first's laser apex
  EXPECT_LT((eyes.at[1] - first.at[1]).norm(), 1e-9);   // its camera
  EXPECT_LT((eyes.at[2] - second.at[1]).norm(), 1e-9);  // and the second's, where it stands
}

TEST(SensorViewCameras, OnlyTwoDistinctCamerasOfTheSameSweepMerge) {
  const SensorView a = stripe(300.0);
  EXPECT_FALSE(with_second_camera(a, a)) << "the same camera twice";
  SensorView other_range = stripe(-300.0);
  other_range.sweep_max = 90.0;
  EXPECT_FALSE(with_second_camera(a, other_range));
  SensorView tilted = stripe(-300.0);
  tilted.plane_normal = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()) * tilted.plane_normal;
  EXPECT_FALSE(with_second_camera(a, tilted));
  EXPECT_FALSE(with_second_camera(a, stripe(-300.0, {0.0, 3.0, 600.0}))) << "another plane";
  SensorView no_camera = stripe(0.0);
  EXPECT_FALSE(with_second_camera(a, no_camera));
  const std::optional<SensorView> both = with_second_camera(a, stripe(-300.0));
  ASSERT_TRUE(both);
  EXPECT_FALSE(with_second_camera(*both, stripe(-200.0))) << "a third camera";
  SensorView point;
  point.kind = SensorView::Kind::kPoint;
  EXPECT_FALSE(with_second_camera(point, point));
}

}  // namespace sensor_view_test
}  // namespace rangefit
