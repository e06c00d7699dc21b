// Writes a varied scene (sim/varied_scene.hpp) as PLY so a person can look at it, and prints
// what was drawn.
//   varied_scene_ply TARGET SEED OUT.ply [pan-tilt]
// TARGET: sphere, cylinder, box, cone, mallet, three_spheres, none; or thesis:TARGET for the
// thesis scene under the stripe cell of the independent scans (45 deg, 0.7 mm, sigma 0.1 mm).
// Also writes OUT.target.ply with the target's points alone.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>

#include "io/ply.hpp"
#include "sim/varied_scene.hpp"

int main(int argc, char** argv) {
  using namespace rangefit;
  if (argc < 4) {
    std::cerr << "usage: varied_scene_ply TARGET SEED OUT.ply [pan-tilt]\n";
    return 1;
  }
  std::string name = argv[1];
  const bool thesis = name.rfind("thesis:", 0) == 0;
  if (thesis) name = name.substr(7);
  sim::VariedTarget target = sim::VariedTarget::kNone;
  bool known = false;
  for (int t = 0; t <= static_cast<int>(sim::VariedTarget::kNone); ++t) {
    if (name == sim::to_string(static_cast<sim::VariedTarget>(t))) {
      target = static_cast<sim::VariedTarget>(t);
      known = true;
    }
  }
  if (!known) {
    std::cerr << "varied_scene_ply: unknown target " << name << "\n";
    return 1;
  }
  const std::uint64_t seed = std::stoull(argv[2]);
  const bool pan_tilt = argc > 4 && std::string(argv[4]) == "pan-tilt";
  const auto t0 = std::chrono::steady_clock::now();
  sim::VariedScene s;
  if (thesis) {
    sim::ScanSetup scan;
    scan.pan_tilt = pan_tilt;
    s = sim::thesis_scene(target, scan, seed);
  } else {
    sim::VariedSceneOptions o;
    o.target = target;
    o.pan_tilt = pan_tilt;
    s = sim::make_varied_scene(o, seed);
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const auto& f = s.factors;
  std::printf(
      "%zu points in %.0f ms: %s, %d profiles x %d rays, fan %.1f deg\n"
      "triangulation %.1f deg side %+d, laser height %.0f mm tilt %.1f deg, step %.2f mm, "
      "noise %.2f mm, outliers %.4f\n"
      "occlusion %.2f (asked %.2f, %s), outside %.2f, look-alikes %d (ratio %.3f), clutter %d\n",
      s.cloud.size(), ms, f.scan.pan_tilt ? "pan-tilt" : "stripe cell", s.sweep.profiles,
      s.sweep.rays, s.sweep.fan_rad * 180.0 / 3.141592653589793, f.scan.triangulation_deg,
      f.scan.camera_side, f.scan.laser_height_mm, f.scan.laser_tilt_deg, f.scan.step_mm,
      f.scan.noise_mm, f.scan.outlier_share, f.occlusion, f.occlusion_requested, f.occluder.c_str(),
      f.outside, f.lookalikes, f.lookalike_ratio, f.clutter);
  for (std::size_t i = 0; i < s.parts.size(); ++i) {
    const auto& p = s.parts[i];
    const Eigen::Vector3d c = p.T_world_part.translation(), z = p.T_world_part.linear().col(2);
    std::printf("  part %zu %-22s a %.1f %.1f %.1f at (%.1f, %.1f, %.1f) z (%.2f, %.2f, %.2f)\n", i,
                p.name.c_str(), p.model.a1, p.model.a2, p.model.a3, c.x(), c.y(), c.z(), z.x(),
                z.y(), z.z());
  }
  try {
    io::write_ply(argv[3], s.cloud);
    PointCloud t;
    for (std::size_t i = 0; i < s.cloud.size(); ++i) {
      for (int k : s.target_parts) {
        if (s.label[i] == k) t.points.push_back(s.cloud.points[i]);
      }
    }
    std::printf("%zu target points\n", t.size());
    io::write_ply(std::string(argv[3]) + ".target.ply", t);
  } catch (const std::exception& e) {
    std::cerr << "varied_scene_ply: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
