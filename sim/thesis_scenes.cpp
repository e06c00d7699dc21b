// thesis_scene (sim/varied_scene.hpp): the object scenes of thesis chapter 5 with the poses of
// test/detect/object_scenes.hpp, scanned by a laser-stripe sweep instead of a pinhole render.
#include <algorithm>

#include "sim/scene_objects.hpp"
#include "sim/varied_scene.hpp"

namespace rangefit::sim {
namespace {

Eigen::Isometry3d pose_from_axis(const Eigen::Vector3d& centre, const Eigen::Vector3d& z,
                                 double spin_rad = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z.normalized()) *
                Eigen::AngleAxisd(spin_rad, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  T.translation() = centre;
  return T;
}

ObjectModel single(const std::string& name, const Superquadric& sq) {
  return ObjectModel{name, {ModelPart{name, sq}}, {}};
}

// Figure 5.18, table 5.3 poses.
std::vector<ScenePart> fig_5_18() {
  return {{"cylinder", cylinder_model(),
           pose_from_axis({153.646, 146.348, 58.275}, {-0.35028, -0.33886, 0.87319})},
          {"box", box_model(),
           pose_from_axis({88.923, 94.128, 59.173}, {0.18692, -0.29300, 0.93767}, 0.3)},
          {"sphere", sphere_model(), pose_from_axis({160.0, 65.0, 50.0}, {0, 0, 1})},
          {"cone", cone_model(), pose_from_axis({213.074, 110.438, 40.0}, {0, 0, 1})}};
}

// Figure 5.28: radii 48, 50 and 52, 10 mm apart.
std::vector<ScenePart> three_spheres() {
  return {{"sphere48", {48, 48, 48, 1, 1, 0, 0}, pose_from_axis({40, 100, 48}, {0, 0, 1})},
          {"sphere50", {50, 50, 50, 1, 1, 0, 0}, pose_from_axis({148, 100, 50}, {0, 0, 1})},
          {"sphere52", {52, 52, 52, 1, 1, 0, 0}, pose_from_axis({260, 100, 52}, {0, 0, 1})}};
}

// The mallet (parts 0, 1) among look-alikes and two occluding boxes.
std::vector<ScenePart> mallet_scene() {
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
  return {
      {"mallet/head", {30, 30, 56, 0.1, 1.0, 0, 0}, pose_from_axis({60, 240, 30}, x)},
      {"mallet/shaft", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({60, 70, 30}, y, 1.5708)},
      {"lookalike/drum", {30, 30, 56, 0.1, 1.0, 0, 0}, pose_from_axis({250, 60, 30}, y)},
      {"lookalike/rod", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({250, 300, 12}, {1, 0.2, 0})},
      {"hammer/head", {15, 15, 45, 0.1, 1.0, 0, 0}, pose_from_axis({320, 200, 15}, y)},
      {"hammer/shaft", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({320, 35, 12}, y)},
      {"occluder/box", {20, 40, 25, 0.1, 0.1, 0, 0}, pose_from_axis({115, 120, 25}, {0, 0, 1})},
      {"occluder/block", {15, 15, 35, 0.1, 0.1, 0, 0}, pose_from_axis({265, -10, 35}, {0, 0, 1})}};
}

}  // namespace

VariedScene thesis_scene(VariedTarget which, const ScanSetup& scan, std::uint64_t seed,
                         int threads) {
  std::vector<ScenePart> parts;
  std::vector<int> target;
  ObjectModel model;
  VariedScene::Factors f;
  f.scan = scan;
  switch (which) {
    case VariedTarget::kCylinder:
    case VariedTarget::kBox:
    case VariedTarget::kSphere:
    case VariedTarget::kCone: {
      parts = fig_5_18();
      const int i = which == VariedTarget::kCylinder ? 0
                    : which == VariedTarget::kBox    ? 1
                    : which == VariedTarget::kSphere ? 2
                                                     : 3;
      target = {i};
      model =
          single(parts[static_cast<std::size_t>(i)].name, parts[static_cast<std::size_t>(i)].model);
      f.clutter = 3;
      break;
    }
    case VariedTarget::kThreeSpheres:
      parts = three_spheres();
      target = {1};
      model = single("sphere", sphere_model());
      f.lookalike_ratio = 0.04;
      f.lookalikes = 2;
      break;
    case VariedTarget::kMallet:
    case VariedTarget::kNone:
      parts = mallet_scene();
      model = mallet_model();
      f.lookalikes = 3;  // drum, rod, hammer
      f.clutter = 2;     // the boxes
      if (which == VariedTarget::kMallet) {
        target = {0, 1};
      } else {
        parts.erase(parts.begin(), parts.begin() + 2);
      }
      break;
  }
  // Sweep across the parts' bounds (and 20 mm around them).
  Eigen::AlignedBox3d cover;
  for (const ScenePart& p : parts) {
    const Eigen::AlignedBox3d b = part_bounds(p.model);
    for (int c = 0; c < 8; ++c) {
      cover.extend(p.T_world_part * b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
    }
  }
  cover.min() -= Eigen::Vector3d(20, 20, 0);
  cover.max() += Eigen::Vector3d(20, 20, 0);
  cover.min().z() = 0.0;
  return scan_varied_scene(std::move(parts), std::move(target), std::move(model),
                           make_sweep(scan, cover), std::move(f), seed, threads);
}

}  // namespace rangefit::sim
