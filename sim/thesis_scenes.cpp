// thesis_scene (sim/varied_scene.hpp): the object scenes of thesis chapter 5 (their parts and
// poses: sim/scene_objects.hpp), scanned by a laser-stripe sweep instead of a pinhole render.
#include <algorithm>

#include "sim/scene_objects.hpp"
#include "sim/varied_scene.hpp"

namespace rangefit::sim {

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
      parts = fig_5_18_parts();
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
      parts = three_spheres_parts();
      target = {1};
      model = single("sphere", sphere_model());
      f.lookalike_ratio = 0.04;
      f.lookalikes = 2;
      break;
    case VariedTarget::kMallet:
    case VariedTarget::kNone:
      parts = mallet_scene_parts();
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
