#include "sim/varied_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "sim/scene_objects.hpp"
#include "sim/stripe_scan.hpp"

namespace rangefit::sim {
namespace varied_scene_test {

constexpr std::array<VariedTarget, 7> kTargets = {
    VariedTarget::kSphere, VariedTarget::kCylinder,     VariedTarget::kBox, VariedTarget::kCone,
    VariedTarget::kMallet, VariedTarget::kThreeSpheres, VariedTarget::kNone};

// Coarse scans: the tests stay fast.
VariedSceneOptions quick(VariedTarget target, bool pan_tilt = false) {
  VariedSceneOptions o;
  o.target = target;
  o.pan_tilt = pan_tilt;
  o.step_min_mm = 1.5;
  o.step_max_mm = 2.0;
  o.max_points = 6000;
  return o;
}

// Scenes whose scan does not matter to the test.
VariedSceneOptions tiny(VariedTarget target, bool pan_tilt = false) {
  VariedSceneOptions o = quick(target, pan_tilt);
  o.max_points = 2000;
  return o;
}

VariedSceneOptions exact(VariedTarget target, bool pan_tilt = false) {
  VariedSceneOptions o = quick(target, pan_tilt);
  o.noise_max_mm = 0.0;
  o.outlier_share_max = 0.0;
  return o;
}

ProfilePose pose_of(const VariedScene& s, std::size_t i) {
  return s.sweep.pose(s.sweep.position(s.profile[i]));
}

// Lowest point of a part's surface on a fine latitude/longitude grid.
double lowest_z(const ScenePart& p) {
  double z = INFINITY;
  for (int i = 0; i <= 32; ++i) {
    for (int j = 0; j < 64; ++j) {
      const Eigen::Vector3d q = p.T_world_part * surface_point(p.model, -M_PI / 2 + M_PI * i / 32,
                                                               -M_PI + 2 * M_PI * j / 64);
      z = std::min(z, q.z());
    }
  }
  return z;
}

TEST(VariedScene, IsTheSameForTheSameSeedWhateverTheThreadCount) {
  VariedSceneOptions o = quick(VariedTarget::kMallet);
  o.threads = 1;
  const VariedScene a = make_varied_scene(o, 7);
  o.threads = 3;
  const VariedScene b = make_varied_scene(o, 7);
  ASSERT_GT(a.cloud.size(), 1000u);
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  for (std::size_t i = 0; i < a.cloud.size(); ++i) {
    ASSERT_EQ(a.cloud.points[i], b.cloud.points[i]);
    ASSERT_EQ(a.label[i], b.label[i]);
  }
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (std::size_t i = 0; i < a.parts.size(); ++i) {
    EXPECT_TRUE(a.parts[i].T_world_part.isApprox(b.parts[i].T_world_part, 0.0));
  }
  EXPECT_EQ(a.cloud.grid.index, b.cloud.grid.index);
  const VariedScene c = make_varied_scene(o, 8);
  EXPECT_NE(a.factors.scan.triangulation_deg, c.factors.scan.triangulation_deg);
}

// Noise moves a point along its laser ray only: the ray through it from its profile's apex meets
// the labelled surface within a few sigma of it.
TEST(VariedScene, PointsLieOnTheirLabelledSurfacesWithinTheNoise) {
  for (bool pan_tilt : {false, true}) {
    VariedSceneOptions o = quick(VariedTarget::kCylinder, pan_tilt);
    o.noise_min_mm = o.noise_max_mm = 0.3;
    const VariedScene s = make_varied_scene(o, 3);
    int on_parts = 0, outliers = 0;
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
      const Eigen::Vector3d& p = s.cloud.points[i];
      const Eigen::Vector3d apex = pose_of(s, i).apex, dir = (p - apex).normalized();
      const double range = (p - apex).norm();
      if (s.label[i] == kOutlierLabel) {
        ++outliers;
        continue;
      }
      double t = -apex.z() / dir.z();  // the table
      if (s.label[i] >= 0) {
        const ScenePart& part = s.parts[static_cast<std::size_t>(s.label[i])];
        const auto hit = intersect_superquadric(part.model, part.T_world_part, apex, dir, 1e5);
        ASSERT_TRUE(hit) << "point " << i << " on " << part.name;
        t = *hit;
        ++on_parts;
      }
      ASSERT_NEAR(range, t, 5.0 * 0.3) << "point " << i << " label " << s.label[i];
    }
    EXPECT_GT(on_parts, 200);
    EXPECT_LE(outliers, static_cast<int>(0.002 * static_cast<double>(s.cloud.size())) + 5);
  }
}

// Every point was seen by both eyes of its profile: nothing between it and the laser apex,
// nothing between it and the camera, and its surface faces the camera.
TEST(VariedScene, NoPointLiesInALaserOrCameraShadow) {
  for (bool pan_tilt : {false, true}) {
    for (VariedTarget t : {VariedTarget::kBox, VariedTarget::kCone, VariedTarget::kMallet}) {
      const VariedScene s = make_varied_scene(exact(t, pan_tilt), 11);
      const PartCaster caster(s.parts);
      for (std::size_t i = 0; i < s.cloud.size(); ++i) {
        const Eigen::Vector3d& p = s.cloud.points[i];
        const ProfilePose pose = pose_of(s, i);
        for (const ScenePart& part : s.parts) {
          ASSERT_FALSE(intersect_superquadric(part.model, part.T_world_part, pose.apex,
                                              p - pose.apex, 1.0 - 1e-5))
              << "laser shadow of " << part.name << " on point " << i;
          ASSERT_FALSE(
              intersect_superquadric(part.model, part.T_world_part, p, pose.camera - p, 1.0, 1e-5))
              << "camera shadow of " << part.name << " on point " << i;
        }
        ASSERT_GT(caster.normal(s.label[i], p).dot(pose.camera - p), 0.0);
      }
      // Shadows exist: far fewer points than rays.
      EXPECT_LT(s.cloud.size(), 0.97 * s.sweep.profiles * s.sweep.rays);
    }
  }
}

// With a second camera across the laser plane, every point was lit by the laser and seen by at
// least one camera; some were seen by only one, and the sensor view names all three eyes.
TEST(VariedScene, WithTwoCamerasEveryPointWasSeenByTheLaserAndOneCamera) {
  for (bool pan_tilt : {false, true}) {
    VariedSceneOptions o = exact(VariedTarget::kBox, pan_tilt);
    o.two_camera_probability = 1.0;
    const VariedScene s = make_varied_scene(o, 11);
    ASSERT_TRUE(s.factors.scan.two_cameras);
    const PartCaster caster(s.parts);
    int only_first = 0, only_second = 0;
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
      const Eigen::Vector3d& p = s.cloud.points[i];
      const ProfilePose pose = pose_of(s, i);
      ASSERT_TRUE(pose.second_camera);
      ASSERT_FALSE(caster.blocked(pose.apex, p, s.label[i])) << "laser shadow on point " << i;
      const Eigen::Vector3d n = caster.normal(s.label[i], p);
      const bool first =
          n.dot(pose.camera - p) > 0.0 && !caster.blocked(p, pose.camera, s.label[i]);
      const bool second = n.dot(*pose.second_camera - p) > 0.0 &&
                          !caster.blocked(p, *pose.second_camera, s.label[i]);
      ASSERT_TRUE(first || second) << "point " << i << " in both cameras' shadows";
      only_first += first && !second;
      only_second += second && !first;
      const Eyes eyes = sensor_eyes(s.view, p);
      ASSERT_EQ(eyes.count, 3) << "point " << i;
      const double tolerance = 0.05 * s.factors.scan.step_mm;
      ASSERT_LT((eyes.at[1] - pose.camera).norm(), tolerance) << "point " << i;
      ASSERT_LT((eyes.at[2] - *pose.second_camera).norm(), tolerance) << "point " << i;
    }
    EXPECT_GT(only_first, 0);
    EXPECT_GT(only_second, 0);
  }
}

TEST(VariedScene, FactorsLieInTheirRangesAndVaryOverSeeds) {
  for (bool pan_tilt : {false, true}) {
    const VariedSceneOptions o = tiny(VariedTarget::kSphere, pan_tilt);
    double tri_lo = INFINITY, tri_hi = -INFINITY, h_lo = INFINITY, h_hi = -INFINITY;
    int plus = 0, minus = 0;
    for (std::uint64_t seed = kTuningSeedBase; seed < kTuningSeedBase + 8; ++seed) {
      const VariedScene s = make_varied_scene(o, seed);
      const auto& f = s.factors;
      EXPECT_EQ(f.scan.pan_tilt, pan_tilt);
      EXPECT_GE(f.scan.triangulation_deg, o.triangulation_min_deg);
      EXPECT_LE(f.scan.triangulation_deg, o.triangulation_max_deg);
      EXPECT_GE(f.scan.laser_height_mm, o.laser_height_min_mm);
      EXPECT_LE(f.scan.laser_height_mm, o.laser_height_max_mm);
      if (pan_tilt) {
        EXPECT_GE(f.scan.laser_tilt_deg, o.pan_tilt_view_min_deg);
        EXPECT_LE(f.scan.laser_tilt_deg, o.pan_tilt_view_max_deg);
      } else {
        EXPECT_LE(std::abs(f.scan.laser_tilt_deg), o.laser_tilt_max_deg);
      }
      EXPECT_GE(f.scan.step_mm, o.step_min_mm);
      EXPECT_LE(f.scan.step_mm, o.step_max_mm);
      EXPECT_GE(f.scan.noise_mm, o.noise_min_mm);
      EXPECT_LE(f.scan.noise_mm, o.noise_max_mm);
      EXPECT_LE(f.scan.outlier_share, o.outlier_share_max);
      EXPECT_GE(f.occlusion_requested, o.occlusion_min);
      EXPECT_LE(f.occlusion_requested, o.occlusion_max);
      EXPECT_GE(f.lookalike_ratio, o.lookalike_min);
      EXPECT_LE(f.lookalike_ratio, o.lookalike_max);
      EXPECT_LE(f.clutter, o.clutter_max);
      // The rays give way to the cap down to their minimum of 16 (these scans are tiny).
      EXPECT_TRUE(s.sweep.profiles * s.sweep.rays <= o.max_points || s.sweep.rays == 16);
      (f.scan.camera_side > 0 ? plus : minus) += 1;
      tri_lo = std::min(tri_lo, f.scan.triangulation_deg);
      tri_hi = std::max(tri_hi, f.scan.triangulation_deg);
      h_lo = std::min(h_lo, f.scan.laser_height_mm);
      h_hi = std::max(h_hi, f.scan.laser_height_mm);
    }
    EXPECT_GT(plus, 0);
    EXPECT_GT(minus, 0);
    EXPECT_GT(tri_hi - tri_lo, 10.0);
    EXPECT_GT(h_hi - h_lo, 150.0);
  }
}

// A head's cameras turn with it; drawn so that none passes under the table top at any profile
// (it would see the parts through the table). Steep views with a wide baseline on the lower side
// took cameras down to 90 mm below it, on one or two cameras alike.
TEST(VariedScene, ThePanTiltHeadsCamerasStayAboveTheTable) {
  VariedSceneOptions o = tiny(VariedTarget::kBox, true);
  o.two_camera_probability = 0.5;
  int low_baseline_side = 0;
  for (std::uint64_t seed = kTuningSeedBase; seed < kTuningSeedBase + 40; ++seed) {
    const VariedScene s = make_varied_scene(o, seed);
    for (int i = 0; i < s.sweep.profiles; ++i) {
      const ProfilePose pose = s.sweep.pose(s.sweep.position(i));
      ASSERT_GE(pose.camera.z(), 50.0) << "seed " << seed << " profile " << i;
      if (pose.second_camera) {
        ASSERT_GE(pose.second_camera->z(), 50.0) << "seed " << seed << " profile " << i;
      }
    }
    low_baseline_side += s.factors.scan.camera_side < 0 && !s.factors.scan.two_cameras;
  }
  EXPECT_GT(low_baseline_side, 0);  // the lower side is still drawn
}

// An exact scene at 1.25 mm steps, never cut by the sweep's end, and the scan of its target
// alone on the same sweep: what the scene's occluders and clutter took is the difference.
std::pair<VariedScene, StripeScan> scene_and_target_alone(VariedTarget t, std::uint64_t seed,
                                                          bool pan_tilt) {
  VariedSceneOptions o = exact(t, pan_tilt);
  o.step_min_mm = o.step_max_mm = 1.25;
  o.max_points = 30000;
  o.partly_outside_probability = 0.0;
  VariedScene s = make_varied_scene(o, seed);
  std::vector<ScenePart> alone;
  for (int k : s.target_parts) alone.push_back(s.parts[static_cast<std::size_t>(k)]);
  StripeScan scan = scan_stripe(PartCaster(alone), s.sweep, {});
  return {std::move(s), std::move(scan)};
}

// The occluder hides about the share drawn; the share reported is what the scan shows: the
// target's points in the scene against its points scanned alone.
TEST(VariedScene, AchievedOcclusionIsTheDrawnOneAndWhatTheScanShows) {
  int walls = 0, overhangs = 0;
  for (VariedTarget t : {VariedTarget::kSphere, VariedTarget::kCylinder, VariedTarget::kBox,
                         VariedTarget::kCone, VariedTarget::kMallet, VariedTarget::kThreeSpheres}) {
    for (std::uint64_t seed : {21}) {
      const bool pan_tilt = t == VariedTarget::kCylinder || t == VariedTarget::kMallet;
      const auto [s, scan] = scene_and_target_alone(t, seed, pan_tilt);
      const auto count = [](const std::vector<std::int32_t>& labels, auto in) {
        return static_cast<double>(std::count_if(labels.begin(), labels.end(), in));
      };
      const double n_alone = count(scan.label, [](std::int32_t l) { return l >= 0; });
      const std::vector<int>& parts = s.target_parts;  // a lambda cannot name a binding
      const double n_scene = count(s.label, [&parts](std::int32_t l) {
        return std::find(parts.begin(), parts.end(), l) != parts.end();
      });
      ASSERT_GT(n_alone, 300.0) << to_string(t) << " seed " << seed;
      const double shown = 1.0 - n_scene / n_alone;
      EXPECT_NEAR(s.factors.occlusion, shown, 0.05) << to_string(t) << " seed " << seed;
      EXPECT_NEAR(s.factors.occlusion, s.factors.occlusion_requested, 0.1)
          << to_string(t) << " seed " << seed << " " << s.factors.occluder;
      walls += s.factors.occluder == "wall";
      overhangs += s.factors.occluder == "overhang";
    }
  }
  EXPECT_GT(walls, 0);
  EXPECT_GT(overhangs, 0);
}

// part_lost: the largest share of one target part that the scan lacks, as the scan's labels show
// it (each part scanned alone against its points in the scene); at least the whole target's
// occlusion, and for a one-part target that occlusion.
TEST(VariedScene, PartLostIsTheLargestShareOfOnePartTheScanLacks) {
  int larger = 0;
  for (VariedTarget t : {VariedTarget::kCylinder, VariedTarget::kMallet}) {
    for (std::uint64_t seed : {21, 22, 23}) {
      const auto [s, scan] = scene_and_target_alone(t, seed, false);
      double shown_lost = 0.0;
      for (std::size_t i = 0; i < s.target_parts.size(); ++i) {
        const auto n_alone =
            std::count(scan.label.begin(), scan.label.end(), static_cast<std::int32_t>(i));
        const auto n_scene = std::count(s.label.begin(), s.label.end(), s.target_parts[i]);
        ASSERT_GT(n_alone, 100) << to_string(t) << " seed " << seed << " part " << i;
        shown_lost =
            std::max(shown_lost, 1.0 - static_cast<double>(n_scene) / static_cast<double>(n_alone));
      }
      EXPECT_NEAR(s.factors.part_lost, shown_lost, 0.05) << to_string(t) << " seed " << seed;
      EXPECT_GE(s.factors.part_lost, s.factors.occlusion - 0.02)
          << to_string(t) << " seed " << seed;
      if (t == VariedTarget::kCylinder) {
        EXPECT_NEAR(s.factors.part_lost, s.factors.occlusion, 0.02) << "seed " << seed;
      }
      larger += s.factors.part_lost > s.factors.occlusion + 0.05;
    }
  }
  EXPECT_GT(larger, 0);  // a mallet whose occluder took mostly one part
}

TEST(VariedScene, SensorViewGivesTheEyesOfTheProfileThatMeasuredEachPoint) {
  for (bool pan_tilt : {false, true}) {
    const VariedScene s = make_varied_scene(quick(VariedTarget::kCone, pan_tilt), 5);
    EXPECT_TRUE(valid(s.view));
    EXPECT_EQ(s.view.kind,
              pan_tilt ? SensorView::Kind::kRotarySweep : SensorView::Kind::kLinearSweep);
    const double tolerance = 0.05 * s.factors.scan.step_mm;
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {  // noisy points and outliers too
      const Eyes eyes = sensor_eyes(s.view, s.cloud.points[i]);
      const ProfilePose pose = pose_of(s, i);
      ASSERT_EQ(eyes.count, 2) << "point " << i;
      ASSERT_LT((eyes.at[0] - pose.apex).norm(), tolerance) << "point " << i;
      ASSERT_LT((eyes.at[1] - pose.camera).norm(), tolerance) << "point " << i;
    }
    // The camera is at the drawn triangulation angle from the laser at the scene centre.
    const ProfilePose mid = s.sweep.pose(0.0);
    const Eigen::Vector3d centre =
        s.sweep.apex0 + s.factors.scan.laser_height_mm / -mid.centre.z() * mid.centre;
    const double angle =
        std::acos((mid.apex - centre).normalized().dot((mid.camera - centre).normalized())) *
        180.0 / std::numbers::pi;
    EXPECT_NEAR(angle, s.factors.scan.triangulation_deg, 1e-6);
  }
}

// kNone: look-alikes and clutter, but no part the size of a single-part model, and for the mallet
// no head-sized and shaft-sized pair linked as the model's.
TEST(VariedScene, NoneHoldsNoInstanceOfTheModel) {
  int mallets = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const VariedScene s = make_varied_scene(tiny(VariedTarget::kNone), seed);
    EXPECT_TRUE(s.target_parts.empty());
    EXPECT_FALSE(s.model.parts.empty());
    EXPECT_EQ(s.factors.occluder, "none");
    EXPECT_GT(s.parts.size(), 0u);
    if (s.model.parts.size() == 1) {
      for (const ScenePart& p : s.parts) {
        EXPECT_FALSE(similar_size(p.model, s.model.parts[0].shape, 0.03)) << p.name;
      }
      continue;
    }
    ++mallets;
    const PartLink& link = s.model.links[0];
    for (const ScenePart& head : s.parts) {
      if (!similar_size(head.model, s.model.parts[0].shape, 0.03)) continue;
      for (const ScenePart& shaft : s.parts) {
        if (!similar_size(shaft.model, s.model.parts[1].shape, 0.03)) continue;
        const double d =
            (head.T_world_part.translation() - shaft.T_world_part.translation()).norm();
        const double a = std::acos(
            std::abs(head.T_world_part.linear().col(2).dot(shaft.T_world_part.linear().col(2))));
        EXPECT_FALSE(std::abs(d - link.distance_mm) < 17.0 && std::abs(a - link.angle_rad) < 0.26)
            << head.name << " + " << shaft.name;
      }
    }
  }
  EXPECT_GT(mallets, 0);
}

TEST(VariedScene, TargetIsTheModelRestingOnTheTable) {
  for (VariedTarget t : kTargets) {
    for (std::uint64_t seed : {1, 2}) {
      const VariedScene s = make_varied_scene(tiny(t), seed);
      ASSERT_EQ(s.target_parts.size(), t == VariedTarget::kNone ? 0u : s.model.parts.size());
      double low = INFINITY;
      for (std::size_t i = 0; i < s.target_parts.size(); ++i) {
        const ScenePart& p = s.parts[static_cast<std::size_t>(s.target_parts[i])];
        const Superquadric& m = s.model.parts[i].shape;
        EXPECT_EQ(p.model.a1, m.a1);
        EXPECT_EQ(p.model.a2, m.a2);
        EXPECT_EQ(p.model.a3, m.a3);
        EXPECT_EQ(p.model.kx, m.kx);
        low = std::min(low, lowest_z(p));
      }
      if (!s.target_parts.empty()) {
        EXPECT_NEAR(low, 0.0, 0.3) << to_string(t);
      }
      if (t == VariedTarget::kMallet) {
        const Eigen::Isometry3d &head = s.parts[0].T_world_part, &shaft = s.parts[1].T_world_part;
        EXPECT_NEAR((head.translation() - shaft.translation()).norm(), 170.0, 1e-9);
        EXPECT_NEAR(head.linear().col(2).dot(shaft.linear().col(2)), 0.0, 1e-12);
        EXPECT_NEAR(head.linear().col(2).z(), 0.0, 1e-12);  // the head lies on its side
      }
      if (t == VariedTarget::kCone) {  // standing on its base
        EXPECT_NEAR(s.parts[0].T_world_part.linear().col(2).z(), 1.0, 1e-12);
      }
    }
  }
}

TEST(VariedScene, ObjectsNeitherInterpenetrateNorSinkIntoTheTable) {
  for (VariedTarget t : kTargets) {
    for (std::uint64_t seed : {4, 5}) {
      const VariedScene s = make_varied_scene(tiny(t), seed);
      for (std::size_t i = 0; i < s.parts.size(); ++i) {
        EXPECT_GT(lowest_z(s.parts[i]), -1e-6) << s.parts[i].name;
        for (std::size_t j = i + 1; j < s.parts.size(); ++j) {
          // Touching is allowed (the overhang's plate rests on its leg).
          EXPECT_FALSE(
              boxes_overlap(oriented_bounds(s.parts[i]), oriented_bounds(s.parts[j]), -0.01))
              << to_string(t) << " seed " << seed << ": " << s.parts[i].name << " and "
              << s.parts[j].name;
        }
      }
    }
  }
}

TEST(VariedScene, ThreeSpheresAreTheTargetAndTwoOthersTheRatioOffIt) {
  const VariedScene s = make_varied_scene(quick(VariedTarget::kThreeSpheres), 6);
  ASSERT_EQ(s.target_parts, std::vector<int>{0});
  EXPECT_EQ(s.parts[0].model.a1, 50.0);
  const double r = s.factors.lookalike_ratio;
  int small = 0, large = 0;
  for (const ScenePart& p : s.parts) {
    small += std::abs(p.model.a1 - 50.0 * (1.0 - r)) < 1e-9 && p.model.eps1 == 1.0;
    large += std::abs(p.model.a1 - 50.0 * (1.0 + r)) < 1e-9 && p.model.eps1 == 1.0;
  }
  EXPECT_GE(small, 1);
  EXPECT_GE(large, 1);
}

TEST(VariedScene, WithoutClutterAndTargetTheScanIsAnEmptyTable) {
  VariedSceneOptions o = quick(VariedTarget::kNone);
  o.clutter = false;
  const VariedScene s = make_varied_scene(o, 1);
  EXPECT_TRUE(s.parts.empty());
  EXPECT_TRUE(s.target_parts.empty());
  ASSERT_GT(s.cloud.size(), 1000u);
  for (std::int32_t l : s.label) EXPECT_LT(l, 0);
}

TEST(VariedScene, ThesisScenesKeepTheirPosesUnderAStripeScan) {
  ScanSetup scan;  // the independent scans: 45 deg, step 0.7 mm, sigma 0.1 mm
  scan.max_points = 8000;
  scan.step_mm = 2.0;
  for (VariedTarget t :
       {VariedTarget::kCylinder, VariedTarget::kBox, VariedTarget::kSphere, VariedTarget::kCone}) {
    const VariedScene s = thesis_scene(t, scan, 1);
    ASSERT_EQ(s.parts.size(), 4u);
    ASSERT_EQ(s.target_parts.size(), 1u);
    EXPECT_EQ(s.parts[static_cast<std::size_t>(s.target_parts[0])].name, s.model.name);
    EXPECT_GT(std::count(s.label.begin(), s.label.end(), s.target_parts[0]), 50);
  }
  EXPECT_NEAR(thesis_scene(VariedTarget::kSphere, scan, 1).parts[2].T_world_part.translation().x(),
              160.0, 1e-12);
  const VariedScene spheres = thesis_scene(VariedTarget::kThreeSpheres, scan, 1);
  EXPECT_EQ(spheres.target_parts, std::vector<int>{1});
  EXPECT_EQ(spheres.parts[1].model.a1, 50.0);
  const VariedScene mallet = thesis_scene(VariedTarget::kMallet, scan, 1);
  EXPECT_EQ(mallet.target_parts, (std::vector<int>{0, 1}));
  EXPECT_EQ(mallet.model.name, "mallet");
  const VariedScene none = thesis_scene(VariedTarget::kNone, scan, 1);
  EXPECT_TRUE(none.target_parts.empty());
  EXPECT_EQ(none.parts.size(), mallet.parts.size() - 2);
  for (const ScenePart& p : none.parts) EXPECT_EQ(p.name.rfind("mallet/", 0), std::string::npos);
}

TEST(StripeScan, AnEmptySweepGivesAnEmptyScan) {
  StripeSweep sweep;
  sweep.profiles = 0;
  const StripeScan s = scan_stripe(PartCaster({}), sweep, {});
  EXPECT_TRUE(s.cloud.empty());
  EXPECT_TRUE(s.label.empty());
}

TEST(StripeSweep, FanAndSweepCoverTheBox) {
  for (bool pan_tilt : {false, true}) {
    ScanSetup setup;
    setup.pan_tilt = pan_tilt;
    setup.laser_tilt_deg = pan_tilt ? 30.0 : -8.0;
    const Eigen::AlignedBox3d box(Eigen::Vector3d(-150, -160, 0), Eigen::Vector3d(150, 160, 120));
    const StripeSweep w = make_sweep(setup, box);
    EXPECT_LE(w.profiles * w.rays, setup.max_points);
    const double lo = w.position(0), hi = w.position(w.profiles - 1);
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      const double s = w.position_of(p);
      EXPECT_GE(s, lo - 1e-9);
      EXPECT_LE(s, hi + w.sweep_step);
      const ProfilePose pose = w.pose(s);
      const Eigen::Vector3d d = p - pose.apex;
      EXPECT_NEAR(pose.normal.dot(d), 0.0, 1e-9);  // p is in that profile's plane
      EXPECT_LE(std::abs(std::atan2(pose.line.dot(d), pose.centre.dot(d))), 0.5 * w.fan_rad);
    }
  }
}

static_assert(kTuningSeedBase + kTuningSeedCount <= kHeldOutSeedBase);

}  // namespace varied_scene_test
}  // namespace rangefit::sim
