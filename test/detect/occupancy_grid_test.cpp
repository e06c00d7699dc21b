#include "detect/common/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "detect/common/kdtree.hpp"
#include "detect/object/object_coverage.hpp"
#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace occupancy_grid_test {

// A 400 x 400 mm wall in the plane z = 0, 2 mm grid, seen from 500 mm above its centre.
std::vector<Eigen::Vector3d> wall() {
  std::vector<Eigen::Vector3d> pts;
  for (double x = -200; x <= 200; x += 2.0) {
    for (double y = -200; y <= 200; y += 2.0) pts.emplace_back(x, y, 0.0);
  }
  return pts;
}

const Eigen::Vector3d kEye(0, 0, 500);

TEST(OccupancyGrid, LinesOfSightMeetTheMeasuredSurface) {
  const OccupancyGrid grid(wall(), 4.0);
  ASSERT_FALSE(grid.empty());
  EXPECT_TRUE(grid.occupied({10, 20, 0.5}));
  EXPECT_FALSE(grid.occupied({10, 20, 50}));
  // From a point above the wall, the line to the eye is clear and the line beyond meets the wall.
  const Eigen::Vector3d above(10, 20, 100);
  EXPECT_LT(grid.first_hit(above, kEye, 5.0), 0.0);
  const double behind = grid.first_hit(above, above + 400.0 * (above - kEye).normalized(), 5.0);
  EXPECT_NEAR(behind, 100.0 * (above - kEye).norm() / (kEye.z() - above.z()), 5.0);
  // From below, the wall hides the eye.
  EXPECT_GT(grid.first_hit({10, 20, -100}, kEye, 5.0), 0.0);
  // Beside the wall: nothing on the way.
  EXPECT_LT(grid.first_hit({600, 0, 0}, {600, 0, 500}, 5.0), 0.0);
  // The first cells are skipped: a point on the wall does not hide itself.
  EXPECT_LT(grid.first_hit({10, 20, 0}, kEye, 5.0), 0.0);
}

// The walk passes empty blocks of cells in one go. It must meet what a walk of every half
// cell meets: the same first hit, or none, on lines of sight through a sparse scene (a table,
// two small objects and loose points far apart, so that most blocks are empty and a line
// enters and leaves occupied ones many times).
TEST(OccupancyGrid, SkippingEmptySpaceMeetsWhatEveryStepMeets) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-150.0, 150.0), h(0.0, 120.0);
  std::vector<Eigen::Vector3d> pts;
  for (double x = -150; x <= 150; x += 1.5) {
    for (double y = -150; y <= 150; y += 1.5) pts.emplace_back(x, y, 0.0);
  }
  for (int i = 0; i < 4000; ++i) {  // a ball and a rod
    const Eigen::Vector3d d = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    pts.push_back(Eigen::Vector3d(40, -30, 40) + 25.0 * d);
    pts.emplace_back(-60 + 0.02 * u(rng), 50 + 0.02 * u(rng), 0.4 * h(rng));
  }
  for (int i = 0; i < 300; ++i) pts.emplace_back(u(rng), u(rng), h(rng));  // loose points
  const OccupancyGrid grid(pts, 1.3);
  const auto every_step = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to, double skip) {
    const Eigen::Vector3d d = (to - from).normalized();
    for (double t = std::max(0.0, skip); t <= (to - from).norm(); t += 0.5 * grid.cell_mm()) {
      if (grid.occupied(from + t * d)) return t;
    }
    return -1.0;
  };
  int hits = 0, clear = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d from(u(rng), u(rng), h(rng));
    const Eigen::Vector3d to =
        i % 2 ? Eigen::Vector3d(u(rng), u(rng), 900.0) : Eigen::Vector3d(u(rng), u(rng), -50.0);
    const double fast = grid.first_hit(from, to, 2.0);
    const double slow = every_step(from, to, 2.0);
    ASSERT_EQ(fast < 0.0, slow < 0.0) << "ray " << i;
    if (slow >= 0.0) {
      EXPECT_NEAR(fast, slow, 1e-6) << "ray " << i;
      ++hits;
    } else {
      ++clear;
    }
  }
  EXPECT_GT(hits, 1000);  // both kinds of lines of sight were walked
  EXPECT_GT(clear, 300);
}

TEST(OccupancyGrid, ACoarseGridStaysWithinItsBudget) {
  const OccupancyGrid grid(wall(), 0.01, 1u << 16);
  ASSERT_FALSE(grid.empty());
  EXPECT_GT(grid.cell_mm(), 0.01);
  EXPECT_TRUE(grid.occupied({0, 0, 0}));
}

TEST(OccupancyGrid, EmptyOrNonFiniteInputHoldsNothing) {
  const OccupancyGrid none({}, 2.0);
  EXPECT_TRUE(none.empty());
  EXPECT_LT(none.first_hit({0, 0, 0}, kEye, 0.0), 0.0);
  const std::vector<Eigen::Vector3d> bad = {{std::nan(""), 0, 0}};
  EXPECT_TRUE(OccupancyGrid(bad, 2.0).empty());
  EXPECT_TRUE(OccupancyGrid(wall(), std::nan("")).empty());
  const OccupancyGrid grid(wall(), 4.0);
  EXPECT_FALSE(grid.occupied({std::nan(""), 0, 0}));
  EXPECT_LT(grid.first_hit({0, 0, 100}, {std::nan(""), 0, 0}, 0.0), 0.0);
}

// Figure 5.18 (at 0.6 of its resolution) as a coverage judges it: its points, their search
// tree and occupancy, seen from the scene's eye.
struct Fig518 {
  const test::Scene s = test::fig_5_18_scene(0.0, 1, 0.6);
  const std::vector<Eigen::Vector3d>& pts = s.rendered.cloud.points;
  const KdTree tree{pts};
  const OccupancyGrid grid{pts, 3.0};
  CoverageOptions o = options();

 private:
  CoverageOptions options() const {
    CoverageOptions c;
    c.sensor.kind = SensorView::Kind::kPoint;
    c.sensor.origin = s.eye;
    c.occupancy = &grid;
    return c;
  }
};

// The sphere of figure 5.18 where it is, and moved to the empty table in front of the objects:
// the first covers its visible surface and hides nothing the sensor saw; the second claims
// surface exactly where the sensor saw the table.
TEST(SurfaceCoverage, SeenThroughSeparatesAPartFromFreeSpace) {
  Fig518 f;
  const Superquadric ball = test::sphere_model();
  const Eigen::Isometry3d here = f.s.parts[2].T_world_part;
  Eigen::Isometry3d floating = here;
  floating.translation() = Eigen::Vector3d(40, 0, 80);  // above the empty front of the table
  const SurfaceCoverage at = surface_coverage(ball, here, f.pts, f.tree, f.o);
  const SurfaceCoverage away = surface_coverage(ball, floating, f.pts, f.tree, f.o);
  EXPECT_GT(at.covered, 0.9);
  EXPECT_LT(at.seen_through, 0.02);
  EXPECT_LT(away.covered, 0.1);
  EXPECT_GT(away.seen_through, 0.8);
  f.o.occupancy = nullptr;  // without the scan's cells nothing is counted as seen through
  EXPECT_EQ(surface_coverage(ball, floating, f.pts, f.tree, f.o).seen_through, 0.0);
}

// The detector takes the surface samples first and the ends and rims only for a part that passes
// them: taken apart, the measures are those taken at once. The fig. 5.18 box where it is and slid
// 20 mm along its axis, off the end of its points, where its ends and rims stand open.
TEST(SurfaceCoverage, MeasuresTakenApartAreThoseTakenAtOnce) {
  Fig518 f;
  const Superquadric box = test::box_model();
  Eigen::Isometry3d slid = f.s.parts[1].T_world_part;
  slid.translation() += 20.0 * slid.linear().col(2);
  double open = 0.0;
  for (const Eigen::Isometry3d& T : {f.s.parts[1].T_world_part, slid}) {
    const SurfaceCoverage whole = surface_coverage(box, T, f.pts, f.tree, f.o);
    SurfaceCoverage c = surface_coverage(box, T, f.pts, f.tree, f.o, kSurfaceOnly);
    EXPECT_EQ(c.open_rim, 0.0);  // not measured
    EXPECT_EQ(c.open_end, 0.0);
    EXPECT_EQ(c.facing, whole.facing);
    EXPECT_EQ(c.covered, whole.covered);
    EXPECT_EQ(c.seen_through, whole.seen_through);
    EXPECT_EQ(c.lowest_mm, whole.lowest_mm);
    take_edges(c, surface_coverage(box, T, f.pts, f.tree, f.o, kEndsAndRims));
    EXPECT_EQ(c.open_end, whole.open_end);
    EXPECT_EQ(c.open_rim, whole.open_rim);
    EXPECT_EQ(c.open_rim_far, whole.open_rim_far);
    for (int end = 0; end < 2; ++end) {
      EXPECT_EQ(c.open_end_at[end], whole.open_end_at[end]);
      EXPECT_EQ(c.open_end_far_at[end], whole.open_end_far_at[end]);
      EXPECT_EQ(c.end_hidden[end], whole.end_hidden[end]);
      EXPECT_EQ(surface_coverage(box, T, f.pts, f.tree, f.o, kEndsOnly).open_end_at[end],
                whole.open_end_at[end]);
    }
    open = std::max({open, whole.open_end, whole.open_rim});
  }
  EXPECT_GT(open, 0.3);  // the slid box's ends or rims were measured open
}

// A stripe ranger's camera shadow: the surface of a part that faces the laser but that its camera
// cannot see is not asked for, so a part measured on one flank only is still covered.
TEST(SurfaceCoverage, SurfaceInTheCameraShadowIsNotAskedFor) {
  const Superquadric ball = test::sphere_model();
  const Eigen::Isometry3d T = test::pose_from_axis({0, 0, 50}, {0, 0, 1});
  CoverageOptions o;  // laser from 600 mm above, sweeping along y; camera 45 deg to +y
  o.sensor.kind = SensorView::Kind::kLinearSweep;
  o.sensor.origin = {0, -300, 600};
  o.sensor.direction = Eigen::Vector3d::UnitY();
  o.sensor.plane_normal = Eigen::Vector3d::UnitY();
  o.sensor.camera_offset = {0, 600, 0};
  o.sensor.sweep_min = 0, o.sensor.sweep_max = 600;
  // What this ranger measures of the ball: the surface facing both its laser and its camera.
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 40000; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / 40000, r = std::sqrt(1.0 - z * z), phi = 2.39996 * i;
    const Eigen::Vector3d n(r * std::cos(phi), r * std::sin(phi), z);
    const Eigen::Vector3d p = T * (50.0 * n);
    const Eyes eyes = sensor_eyes(o.sensor, p);
    bool seen = eyes.count == 2;
    for (int k = 0; k < eyes.count; ++k) seen = seen && n.dot(eyes.at[k] - p) > 0.0;
    if (seen) pts.push_back(p);
  }
  const KdTree tree(pts);
  const OccupancyGrid grid(pts, 3.0);
  o.occupancy = &grid;
  const SurfaceCoverage two_eyes = surface_coverage(ball, T, pts, tree, o);
  EXPECT_GT(two_eyes.covered, 0.95);
  EXPECT_LT(two_eyes.seen_through, 0.02);
  o.sensor.camera_offset.setZero();  // as if the laser's eye alone had measured it
  const SurfaceCoverage one_eye = surface_coverage(ball, T, pts, tree, o);
  EXPECT_GT(one_eye.measurable, two_eyes.measurable);
  EXPECT_LT(one_eye.covered, two_eyes.covered - 0.1);  // its camera shadow counted as missing
}

}  // namespace occupancy_grid_test
}  // namespace rangefit
