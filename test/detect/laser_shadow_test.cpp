#include "detect/common/laser_shadow.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rangefit {
namespace laser_shadow_test {

// A stripe ranger 600 mm above the table, its laser plane x = s swept along +x over -100..100,
// its camera 300 mm off the plane along -x. The scan: the table (z = 0) and the top of a wall
// 100 mm high standing across the sweep at y = 50..60, whose faces the vertical laser grazed.
SensorView stripe() {
  SensorView v;
  v.kind = SensorView::Kind::kLinearSweep;
  v.origin = {0, 0, 600};
  v.plane_normal = Eigen::Vector3d::UnitX();
  v.direction = Eigen::Vector3d::UnitX();
  v.camera_offset = {-300, 0, 0};
  v.sweep_min = -100, v.sweep_max = 100;
  return v;
}

std::vector<Eigen::Vector3d> table_and_wall_top() {
  std::vector<Eigen::Vector3d> pts;
  for (double x = -100; x <= 100; x += 1.0) {
    for (double y = -100; y <= 100; y += 1.0) {
      const bool wall = y >= 50.0 && y <= 60.0;
      pts.emplace_back(x, y, wall ? 100.0 : 0.0);
    }
  }
  return pts;
}

TEST(LaserShadow, SpaceUnderAGrazedWallsTopIsInShadow) {
  const std::vector<Eigen::Vector3d> pts = table_and_wall_top();  // the shadow borrows them
  const LaserShadow shadow(pts, stripe(), 2.0);
  ASSERT_FALSE(shadow.empty());
  EXPECT_TRUE(shadow.shadowed({0, 55, 50}, 3.0));    // inside the wall
  EXPECT_FALSE(shadow.shadowed({0, 55, 110}, 3.0));  // above it
  EXPECT_FALSE(shadow.shadowed({0, 0, 50}, 3.0));    // over the lit table
  EXPECT_FALSE(shadow.shadowed({0, 0, 1}, 3.0));     // on it, within the margin
  // A line of sight from the table beside the wall to a camera beyond it passes through the
  // wall's body, which the grid of measured surface would not know of.
  const Eigen::Vector3d from(0, 20, 0), to(0, 300, 600);
  const double t = shadow.first_shadowed(from, to, 2.0, 1.0, 3.0);
  ASSERT_GT(t, 0.0);
  const Eigen::Vector3d at = from + t * (to - from).normalized();
  EXPECT_NEAR(at.y(), 50.0, 3.0);
  // Away from the wall the line stays clear.
  EXPECT_LT(shadow.first_shadowed(from, {0, -300, 600}, 2.0, 1.0, 3.0), 0.0);
}

// A pan-tilt head: its laser fan, apex at the pivot 600 mm above the table, turns about the
// y-axis from -0.3 to 0.3 rad, its camera 300 mm off the fan's plane. Over the same table and
// wall, space under the wall's top is in shadow wherever along the turn it is.
TEST(LaserShadow, ATurningFansShadowUnderAGrazedWall) {
  SensorView head;
  head.kind = SensorView::Kind::kRotarySweep;
  head.pivot = head.origin = {0, 0, 600};
  head.direction = Eigen::Vector3d::UnitY();
  head.plane_normal = Eigen::Vector3d::UnitX();
  head.camera_offset = {-300, 0, 0};
  head.sweep_min = -0.3, head.sweep_max = 0.3;
  const std::vector<Eigen::Vector3d> pts = table_and_wall_top();  // the shadow borrows them
  // Bins of 3 mm: the wall's top, 100 mm nearer the apex than the table, holds two returns in each.
  const LaserShadow shadow(pts, head, 3.0);
  ASSERT_FALSE(shadow.empty());
  for (double x : {-80.0, 0.0, 60.0}) {
    // (x, 58, 50) seen from the apex lies behind the wall's top (y 52.7 at z = 100).
    EXPECT_TRUE(shadow.shadowed({x, 58, 50}, 3.0)) << x;
    EXPECT_FALSE(shadow.shadowed({x, 58, 110}, 3.0)) << x;
    EXPECT_FALSE(shadow.shadowed({x, 0, 50}, 3.0)) << x;
  }
  const Eigen::Vector3d from(30, 20, 0), to(30, 300, 600);
  const double t = shadow.first_shadowed(from, to, 2.0, 1.0, 3.0);
  ASSERT_GT(t, 0.0);
  EXPECT_NEAR((from + t * (to - from).normalized()).y(), 50.0, 3.0);
  EXPECT_LT(shadow.first_shadowed(from, {30, -300, 600}, 2.0, 1.0, 3.0), 0.0);
}

// A lone return in the air before the surface (an outlier along its ray) casts no shadow column:
// a bin's shadow starts at its second nearest return.
TEST(LaserShadow, ALoneOutlierCastsNoShadow) {
  std::vector<Eigen::Vector3d> pts = table_and_wall_top();
  pts.emplace_back(0.3, -49.7, 300.0);
  const LaserShadow shadow(pts, stripe(), 2.0);
  EXPECT_FALSE(shadow.shadowed({0.3, -49.7, 100.0}, 3.0));
  EXPECT_TRUE(shadow.shadowed({0, 55, 50}, 3.0));
}

// A query may leave out the returns that cast a shadow (the part judged, on its own surface).
TEST(LaserShadow, ReturnsLeftOutByTheQueryCastNothing) {
  const std::vector<Eigen::Vector3d> pts = table_and_wall_top();  // the shadow borrows them
  const LaserShadow shadow(pts, stripe(), 2.0);
  const auto not_wall = [](const Eigen::Vector3d& p) { return p.z() < 50.0; };
  EXPECT_FALSE(shadow.shadowed({0, 55, 50}, 3.0, not_wall));
  EXPECT_LT(shadow.first_shadowed({0, 20, 0}, {0, 300, 600}, 2.0, 1.0, 3.0, not_wall), 0.0);
}

TEST(LaserShadow, OtherViewsAndBadInputCastNoShadow) {
  SensorView point;
  point.kind = SensorView::Kind::kPoint;
  EXPECT_TRUE(LaserShadow(table_and_wall_top(), point, 2.0).empty());
  EXPECT_TRUE(LaserShadow(table_and_wall_top(), SensorView{}, 2.0).empty());
  SensorView one_eye = stripe();
  one_eye.camera_offset = Eigen::Vector3d::Zero();
  EXPECT_TRUE(LaserShadow(table_and_wall_top(), one_eye, 2.0).empty());
  EXPECT_TRUE(LaserShadow({}, stripe(), 2.0).empty());
  EXPECT_TRUE(LaserShadow(table_and_wall_top(), stripe(), std::nan("")).empty());
  const std::vector<Eigen::Vector3d> bad = {{std::nan(""), 0, 0}};
  const LaserShadow none(bad, stripe(), 2.0);
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(none.shadowed({0, 55, 50}, 3.0));
  const std::vector<Eigen::Vector3d> pts = table_and_wall_top();
  const LaserShadow shadow(pts, stripe(), 2.0);
  EXPECT_FALSE(shadow.shadowed({std::nan(""), 0, 0}, 3.0));
  EXPECT_LT(shadow.first_shadowed({0, 20, 0}, {std::nan(""), 0, 0}, 2.0, 1.0, 3.0), 0.0);
  EXPECT_LT(shadow.first_shadowed({0, 20, 0}, {0, 300, 600}, 2.0, 0.0, 3.0), 0.0);
}

}  // namespace laser_shadow_test
}  // namespace rangefit
