#pragma once
// Small laser-stripe scenes for the object tests: parts placed by hand on the table, scanned by
// a stripe cell of a given triangulation angle and camera side (sim/varied_scene.hpp: laser 600 mm
// up, 1 mm profile step), and the detector run with that scan's own sensor model.
#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

#include "detect/object/object_detector.hpp"
#include "sim/varied_scene.hpp"

namespace rangefit::test {

struct StripeGeometry {
  double triangulation_deg;
  int side;  // camera on +1 or -1 side of the laser plane
};

// Both camera sides and two triangulation angles; ASan+UBSan runs ~10x slower: one geometry.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr StripeGeometry kStripeGeometries[] = {{45.0, -1}};
#else
inline constexpr StripeGeometry kStripeGeometries[] = {{20.0, +1}, {45.0, -1}};
#endif

inline sim::ScenePart placed(const std::string& name, const Superquadric& sq,
                             const Eigen::Vector3d& centre, const Eigen::Vector3d& axis) {
  return {name, sq, sim::pose_from_axis(centre, axis)};
}

// The parts scanned by a stripe cell of geometry g over `cover` (the sweep and 30 mm around it).
inline sim::VariedScene stripe_scan(std::vector<sim::ScenePart> parts, std::vector<int> target,
                                    ObjectModel model, const StripeGeometry& g,
                                    std::uint64_t seed, double noise_mm,
                                    const Eigen::AlignedBox3d& cover) {
  sim::VariedScene::Factors f;
  f.scan.triangulation_deg = g.triangulation_deg;
  f.scan.camera_side = g.side;
  f.scan.laser_height_mm = 600.0;
  f.scan.step_mm = 1.0;
  f.scan.noise_mm = noise_mm;
  f.scan.max_points = 60000;
  return sim::scan_varied_scene(std::move(parts), std::move(target), std::move(model),
                                sim::make_sweep(f.scan, cover), f, seed);
}

// The table area most scenes use: 260 mm square, 120 mm high.
inline Eigen::AlignedBox3d table_cover(double y_max_mm = 130.0) {
  return {Eigen::Vector3d(-130, -130, 0), Eigen::Vector3d(130, y_max_mm, 120)};
}

inline ObjectDetectResult detect_in(const sim::VariedScene& s, std::uint64_t seed) {
  ObjectDetectOptions o;
  o.sensor = s.view;
  o.seed = seed;
  return detect_object(s.model, s.cloud.points, o);
}

}  // namespace rangefit::test
