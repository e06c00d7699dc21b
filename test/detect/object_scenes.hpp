#pragma once
// Synthetic single-view test scenes of thesis chapter 5 with ground truth, shared by the object
// detection tests and test/bench/object_benchmark.cpp.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "detect/object/object_model.hpp"
#include "sim/scene_objects.hpp"
#include "sim/superquadric_raycast.hpp"

namespace rangefit::test {

// The thesis's models, poses and scenes' parts are the simulator's (sim/scene_objects.hpp).
using sim::box_model;
using sim::cone_model;
using sim::cylinder_model;
using sim::mallet_model;
using sim::pose_from_axis;
using sim::single;
using sim::sphere_model;

// The view of figures 5.18 and 5.28: ~140,000 points at 440 x 330 rays.
inline sim::SceneView table_view() {
  sim::SceneView view;
  view.fov_deg = 36.0;
  view.table_min = {-100, -80};
  view.table_max = {400, 320};
  return view;
}

struct Scene {
  sim::RenderedScene rendered;
  std::vector<sim::ScenePart> parts;  // ground truth, same order as the labels
  Eigen::Vector3d eye;
};

inline Scene render(std::vector<sim::ScenePart> parts, sim::SceneView view) {
  Scene s;
  s.rendered = sim::render_scene(parts, view);
  s.parts = std::move(parts);
  s.eye = view.eye;
  return s;
}

// Figure 5.18: cylinder, box, sphere and cone of table 5.2 at the poses of table 5.3 (~140,000
// points at the default resolution; `scale` < 1 renders fewer for quick tests).
inline Scene fig_5_18_scene(double noise_sigma = 0.0, std::uint64_t noise_seed = 1,
                            double scale = 1.0) {
  std::vector<sim::ScenePart> parts = sim::fig_5_18_parts();
  sim::SceneView view = table_view();
  view.width = static_cast<int>(std::lround(440 * scale));
  view.height = static_cast<int>(std::lround(330 * scale));
  view.noise_sigma_mm = noise_sigma;
  view.noise_seed = noise_seed;
  return render(std::move(parts), view);
}

// Figure 5.28: spheres of radius 48, 50 and 52 mm, 10 mm apart, on the table; the middle one
// (index 1) is searched for.
inline Scene three_spheres_scene(double noise_sigma, std::uint64_t noise_seed, double scale = 1.0) {
  std::vector<sim::ScenePart> parts = sim::three_spheres_parts();
  sim::SceneView view = table_view();
  view.width = static_cast<int>(std::lround(440 * scale));
  view.height = static_cast<int>(std::lround(330 * scale));
  view.noise_sigma_mm = noise_sigma;
  view.noise_seed = noise_seed;
  return render(std::move(parts), view);
}

// A two-part mallet (head across the end of the shaft, as the model's links say) lying on the
// table among look-alikes (a lone head-sized cylinder, a shaft-sized rod, a hammer with a smaller
// head on a similar shaft) and two occluding boxes. Parts 0 and 1 are the mallet.
inline Scene mallet_scene(double noise_sigma = 0.0, std::uint64_t noise_seed = 1,
                          double scale = 1.0) {
  std::vector<sim::ScenePart> parts = sim::mallet_scene_parts();
  sim::SceneView view;
  view.fov_deg = 42.0;
  view.eye = {180, -220, 480};
  view.target = {180, 130, 20};
  view.table_min = {-80, -80};
  view.table_max = {420, 320};
  view.width = static_cast<int>(std::lround(440 * scale));
  view.height = static_cast<int>(std::lround(330 * scale));
  view.noise_sigma_mm = noise_sigma;
  view.noise_seed = noise_seed;
  return render(std::move(parts), view);
}

// How far a found pose is from the truth: centre distance and the cosine between the z-axes
// (sign ignored for parts symmetric about their equator, i.e. all but tapered ones).
struct PoseError {
  double centre_mm = 0.0;
  double axis_cos = 1.0;
  double axis_deg() const { return std::acos(std::min(1.0, axis_cos)) * 180.0 / std::numbers::pi; }
};

inline PoseError pose_error(const Eigen::Isometry3d& found, const sim::ScenePart& truth) {
  const Eigen::Vector3d a = found.linear().col(2), b = truth.T_world_part.linear().col(2);
  const bool tapered = truth.model.kx != 0.0 || truth.model.ky != 0.0;
  return {(found.translation() - truth.T_world_part.translation()).norm(),
          tapered ? a.dot(b) : std::abs(a.dot(b))};
}

// True positive as in the thesis: centre within 3 mm and, except for spheres, the z-axis within
// 5 degrees.
inline bool true_positive(const Eigen::Isometry3d& found, const sim::ScenePart& truth,
                          bool check_axis = true, double max_centre_mm = 3.0) {
  const PoseError e = pose_error(found, truth);
  if (e.centre_mm > max_centre_mm) return false;
  return !check_axis || e.axis_cos >= std::cos(5.0 * std::numbers::pi / 180.0);
}

}  // namespace rangefit::test
