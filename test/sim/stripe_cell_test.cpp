#include "sim/stripe_cell.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/analytic_shapes.hpp"
#include "sim/pan_tilt_head.hpp"
#include "sim/sim_clock.hpp"

namespace rangefit::sim {
namespace stripe_cell_test {

// The table plus a box and a cylinder standing on it, in the cell's table frame.
Scene table_scene() {
  Scene s;
  s.objects.push_back({"table", PlaneShape{400.0, 400.0}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d box = Eigen::Isometry3d::Identity();
  box.translation() = Eigen::Vector3d(-40.0, 150.0, 40.0);
  s.objects.push_back({"box", BoxShape{Eigen::Vector3d(50.0, 50.0, 80.0)}, box});
  Eigen::Isometry3d cyl = Eigen::Isometry3d::Identity();
  cyl.translation() = Eigen::Vector3d(60.0, 160.0, 50.0);
  s.objects.push_back({"can", CylinderShape{30.0, 100.0}, cyl});
  return s;
}

StripeCellOptions exact_options() {
  StripeCellOptions o;
  o.quantise = false;
  o.profile_rate_hz = 50.0;
  return o;
}

TEST(StripeCell, ProfilesLandOnTheTrueSurfacesAndShadowsAreAbsent) {
  const Scene scene = table_scene();
  const RayCaster caster(scene);
  SimClock clock;
  StripeCell cell(scene, caster, exact_options(), clock);
  const auto& ranger = cell.options().geometry.ranger;
  int valid = 0, camera_shadowed = 0;
  for (double s = 0.0; s <= 120.0; s += 2.0) {
    const Eigen::Isometry3d T = cell.options().geometry.T_world_ranger(s);
    const ProfileTruth t = cast_profile(caster, ranger, T);
    for (int k = 0; k < ranger.points_per_profile; ++k) {
      const auto i = static_cast<std::size_t>(k);
      // Independent check: first hit by brute force, then the camera segment.
      const Eigen::Vector3d d = T.linear() * ranger.ray_direction(k, ranger.points_per_profile);
      const Hit h = caster.cast_brute_force(Ray{T.translation(), d, 0.0, 1e4});
      bool expect = h.valid && ranger.depth_in_range((T.inverse() * h.point).z());
      if (expect) {
        const Eigen::Vector3d to_cam = T * ranger.camera_point() - h.point;
        if (caster.cast_brute_force(Ray{h.point, to_cam.normalized(), 1e-3, to_cam.norm() - 1e-3})
                .valid) {
          expect = false;
          ++camera_shadowed;
        }
      }
      ASSERT_EQ(!std::isnan(t.z_mm[i]), expect) << "axis " << s << " point " << k;
      if (!expect) continue;
      ++valid;
      const SceneObject& obj = scene.objects[t.object[i]];
      ASSERT_LT(surface_distance(obj.shape, obj.T_world_object, t.point_scene[i]), 1e-6);
      ASSERT_LT((T * Eigen::Vector3d(t.x_mm[i], 0.0, t.z_mm[i]) - t.point_scene[i]).norm(), 1e-9);
    }
  }
  EXPECT_GT(valid, 20000);
  EXPECT_GT(camera_shadowed, 100) << "objects must shadow the table for the test to mean anything";
}

// Every column k of a profile's truth describes fan ray k: x/z, point_scene and object agree
// column for column, including where the box's shadow and the table's edge leave gaps.
TEST(StripeCell, ProfileTruthIsAlignedColumnForColumnWithItsFanRays) {
  Scene scene = table_scene();
  std::get<PlaneShape>(scene.objects[0].shape).size_x_mm = 200.0;  // fan reaches past the edges
  const RayCaster caster(scene);
  const hal::StripeCellGeometry g;
  const int n = g.ranger.points_per_profile;
  int valid = 0, gaps = 0;
  for (double s : {0.0, 50.0, 130.0}) {
    const Eigen::Isometry3d T = g.T_world_ranger(s);
    const ProfileTruth t = cast_profile(caster, g.ranger, T);
    ASSERT_EQ(t.point_scene.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(t.object.size(), static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (std::isnan(t.z_mm[i])) {
        ++gaps;
        EXPECT_TRUE(t.point_scene[i].array().isNaN().all()) << "column " << k;
        EXPECT_EQ(t.object[i], -1) << "column " << k;
        continue;
      }
      ++valid;
      const Eigen::Vector3d p_ranger = T.inverse() * t.point_scene[i];
      ASSERT_NEAR(std::atan2(p_ranger.x(), p_ranger.z()), g.ranger.ray_angle(k, n), 1e-9)
          << "column " << k << " at axis " << s;
      ASSERT_NEAR(p_ranger.x(), t.x_mm[i], 1e-9);
      ASSERT_NEAR(p_ranger.z(), t.z_mm[i], 1e-9);
      const SceneObject& obj = scene.objects[static_cast<std::size_t>(t.object[i])];
      ASSERT_LT(surface_distance(obj.shape, obj.T_world_object, t.point_scene[i]), 1e-6);
    }
  }
  EXPECT_GT(valid, 500);
  EXPECT_GT(gaps, 100) << "the profiles must have gaps for the alignment to be tested";
}

TEST(StripeCell, ChipQuantisationKeepsPointsOnTheirFanRayWithinOneRow) {
  hal::StripeRanger r = StripeCellOptions{}.geometry.ranger;
  const double row = (r.max_depth_mm - r.min_depth_mm) / kChipRows;
  for (int k : {0, 100, 255, 511}) {
    const Eigen::Vector3d d = r.ray_direction(k, r.points_per_profile);
    double x = 512.3456 * d.x(), z = 512.3456 * d.z();
    const double z0 = z;
    quantise_to_chip(r, k, x, z);
    EXPECT_LE(std::abs(z - z0), 0.5 * row + 1e-12);
    EXPECT_NEAR(x / z, d.x() / d.z(), 1e-12);
  }
}

TEST(StripeCell, AxisMovesAtMostAtItsTopSpeedAndReportsQuantisedPositions) {
  const Scene scene = table_scene();
  const RayCaster caster(scene);
  SimClock clock;
  StripeCell cell(scene, caster, StripeCellOptions{}, clock);
  hal::LinearAxis& axis = cell.axis();
  EXPECT_FALSE(axis.move_to(10.0, 5.0)) << "refused before enable";
  ASSERT_TRUE(axis.enable());
  EXPECT_FALSE(axis.move_to(1000.0, 5.0)) << "outside the travel";
  ASSERT_TRUE(axis.start());
  ASSERT_TRUE(axis.move_to(63.0, 100.0));  // clamped to 6.3 mm/s
  std::vector<hal::AxisSample> samples;
  while (!axis.motion_complete()) axis.read(samples, std::chrono::milliseconds(200));
  ASSERT_GT(samples.size(), 400u);
  EXPECT_NEAR(static_cast<double>((samples.back().stamp - samples.front().stamp).count()) * 1e-9,
              10.0, 0.1);
  for (const auto& s : samples) {
    EXPECT_NEAR(s.position_mm / 0.05, std::round(s.position_mm / 0.05), 1e-6);
    EXPECT_LE(s.velocity_mm_s, 6.3);
  }
}

TEST(StripeCell, ScanDeliversProfilesWhileTheAxisMoves) {
  const Scene scene = table_scene();
  const RayCaster caster(scene);
  SimClock clock;
  StripeCell cell(scene, caster, StripeCellOptions{}, clock);
  ASSERT_TRUE(cell.axis().enable());
  ASSERT_TRUE(cell.ranger().start());
  ASSERT_TRUE(cell.axis().move_to(20.0, 6.3));
  std::vector<hal::RangerProfile> profiles;
  while (!cell.axis().motion_complete())
    cell.ranger().read(profiles, std::chrono::milliseconds(200));
  ASSERT_GT(profiles.size(), 30u);
  for (const auto& p : profiles) {
    ASSERT_EQ(p.x_mm.size(), 512u);
    ASSERT_EQ(p.z_mm.size(), 512u);
  }
  EXPECT_EQ(cell.ranger().health().counters.samples, profiles.size());
}

TEST(PanTiltHead, SweepProfilesLandOnTheTrueSurfaces) {
  Scene scene = table_scene();
  // Head 800 mm above the table, looking down (ranger z = -scene z).
  scene.mounts.T_scene_pantilt.linear() =
      Eigen::AngleAxisd(3.14159265358979323846, Eigen::Vector3d::UnitX()).toRotationMatrix();
  scene.mounts.T_scene_pantilt.translation() = Eigen::Vector3d(0.0, 150.0, 800.0);
  const RayCaster caster(scene);
  SimClock clock;
  PanTiltOptions o;
  o.quantise = false;
  PanTiltHead head(scene, caster, o, clock);
  int valid = 0;
  for (double t = 0.0; t < 5.0; t += 0.25) {
    const hal::Timestamp at =
        head.sweep_start() + std::chrono::milliseconds(static_cast<int>(t * 1000));
    const ProfileTruth p = cast_profile(caster, o.geometry.ranger, head.T_scene_ranger(at));
    for (std::size_t i = 0; i < p.z_mm.size(); ++i) {
      if (std::isnan(p.z_mm[i])) continue;
      ++valid;
      const SceneObject& obj = scene.objects[p.object[i]];
      ASSERT_LT(surface_distance(obj.shape, obj.T_world_object, p.point_scene[i]), 1e-6);
    }
  }
  EXPECT_GT(valid, 3000);
  ASSERT_TRUE(head.angles().start());
  std::vector<hal::PanTiltSample> angles;
  while (clock.now() < head.sweep_end()) head.angles().read(angles, std::chrono::milliseconds(100));
  ASSERT_GT(angles.size(), 400u);
  EXPECT_NEAR(angles.front().pan_rad, -0.5 * o.geometry.sweep_angle_rad, 1e-6);
  EXPECT_NEAR(angles.back().pan_rad, 0.5 * o.geometry.sweep_angle_rad, 2e-3);
}

}  // namespace stripe_cell_test
}  // namespace rangefit::sim
