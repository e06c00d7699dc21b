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

// A pan-tilt head: its laser fan, apex at the pivot 600 mm above the table, turns about the
// y-axis over -turn..turn rad, its camera 300 mm off the fan's plane.
SensorView pan_tilt(double turn) {
  SensorView v;
  v.kind = SensorView::Kind::kRotarySweep;
  v.pivot = v.origin = {0, 0, 600};
  v.direction = Eigen::Vector3d::UnitY();
  v.plane_normal = Eigen::Vector3d::UnitX();
  v.camera_offset = {-300, 0, 0};
  v.sweep_min = -turn, v.sweep_max = turn;
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

// A pan-tilt head turning over -0.3..0.3 rad: over the same table and wall, space under the
// wall's top is in shadow wherever along the turn it is.
TEST(LaserShadow, ATurningFansShadowUnderAGrazedWall) {
  const SensorView head = pan_tilt(0.3);
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

// A stripe sweep that stopped at x = 0, over the table and the wall's top left of it: space past
// the sweep's end was never lit. A camera on that side looks at a part's face by the end through
// it, and a wall standing there would leave no point; one on the other side looks across the
// lit space, and its line leaves the points' box through the top, above all that was measured.
TEST(LaserShadow, SpaceASweepNeverReachedIsUnlit) {
  SensorView v = stripe();
  v.sweep_max = 0.0;
  v.camera_offset = {300, 0, 0};
  std::vector<Eigen::Vector3d> pts;
  for (const Eigen::Vector3d& p : table_and_wall_top()) {
    if (p.x() <= 0.0) pts.push_back(p);
  }
  const LaserShadow shadow(pts, v, 2.0);
  ASSERT_FALSE(shadow.empty());
  EXPECT_FALSE(shadow.unlit({-50, 0, 50}));  // over the lit table
  EXPECT_TRUE(shadow.unlit({0.5, 0, 50}));   // past the sweep's end
  EXPECT_FALSE(shadow.unlit({std::nan(""), 0, 50}));
  // From a face 5 mm before the end, 10 mm up: to the camera past the end the line leaves the
  // points' box through its side at x = 0, into space the sweep never reached.
  const Eigen::Vector3d from(-5, 0, 10), camera(295, 0, 600);
  const double t = shadow.first_shadowed(from, camera, 2.0, 1.0, 3.0);
  ASSERT_GT(t, 0.0);
  EXPECT_NEAR((from + t * (camera - from).normalized()).x(), 0.0, 1.5);
  // Unless unlit space that far from `from` is taken as clear.
  EXPECT_LT(shadow.first_shadowed(from, camera, 2.0, 1.0, 3.0, nullptr, 4.0), 0.0);
  // Back across the lit space: clear.
  EXPECT_LT(shadow.first_shadowed(from, {-305, 0, 600}, 2.0, 1.0, 3.0), 0.0);
}

// A pan-tilt head's fan turned over -0.1..0.1 rad: its wedge narrows towards the apex, so the
// points' box holds space beside it the laser never lit. Over the lit table beneath, though,
// anything standing there would have hidden the table or shown the laser its surface; beside the
// wall's top, whose ends the wedge cut off, nothing was measured in the column at all.
TEST(LaserShadow, SpaceBesideATurningFansWedgeIsUnlitWhereNothingBeneathWasMeasured) {
  const SensorView head = pan_tilt(0.1);
  std::vector<Eigen::Vector3d> pts;
  for (const Eigen::Vector3d& p : table_and_wall_top()) {
    // What the wedge lit: |x| <= (600 - z) tan 0.1.
    if (std::abs(p.x()) <= (600.0 - p.z()) * std::tan(0.1)) pts.push_back(p);
  }
  const LaserShadow shadow(pts, head, 3.0);
  ASSERT_FALSE(shadow.empty());
  EXPECT_FALSE(shadow.unlit({45, 0, 99}));  // inside the wedge (|x| <= 50.2 at z = 99)
  EXPECT_FALSE(shadow.unlit({57, 0, 99}));  // beside it, over the lit table
  EXPECT_TRUE(shadow.unlit({57, 55, 99}));  // beside it, where the wall's top was cut off
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
