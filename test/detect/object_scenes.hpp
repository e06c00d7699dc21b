#pragma once
// Synthetic single-view test scenes of thesis chapter 5 with ground truth, shared by the object
// detection tests and test/bench/object_benchmark.cpp.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "detect/object_model.hpp"
#include "sim/superquadric_raycast.hpp"

namespace rangefit::test {

inline Eigen::Isometry3d pose_from_axis(const Eigen::Vector3d& centre, const Eigen::Vector3d& z,
                                        double spin_rad = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z.normalized()) *
                Eigen::AngleAxisd(spin_rad, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  T.translation() = centre;
  return T;
}

// Table 5.2 models.
inline Superquadric cylinder_model() { return {30, 30, 50, 0.1, 1.0, 0.0, 0.0}; }
inline Superquadric box_model() { return {25, 25, 50, 0.1, 0.1, 0.0, 0.0}; }
inline Superquadric sphere_model() { return {50, 50, 50, 1.0, 1.0, 0.0, 0.0}; }
inline Superquadric cone_model() { return {20, 20, 40, 0.1, 1.0, -1.0, -1.0}; }

inline ObjectModel single(const std::string& name, const Superquadric& sq) {
  return ObjectModel{name, {ModelPart{name, sq}}, {}};
}

inline ObjectModel mallet_model() {
  ObjectModel m;
  m.name = "mallet";
  m.parts = {{"head", {30, 30, 56, 0.1, 1.0, 0.0, 0.0}},
             {"shaft", {12, 10, 120, 0.1, 1.0, 0.0, 0.0}}};
  m.links = {{0, 1, std::numbers::pi / 2.0, 170.0}};
  return m;
}

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
  std::vector<sim::ScenePart> parts = {
      {"cylinder", cylinder_model(),
       pose_from_axis({153.646, 146.348, 58.275}, {-0.35028, -0.33886, 0.87319})},
      {"box", box_model(),
       pose_from_axis({88.923, 94.128, 59.173}, {0.18692, -0.29300, 0.93767}, 0.3)},
      {"sphere", sphere_model(), pose_from_axis({160.0, 65.0, 50.0}, {0, 0, 1})},
      {"cone", cone_model(), pose_from_axis({213.074, 110.438, 40.0}, {0, 0, 1})}};
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
  std::vector<sim::ScenePart> parts = {
      {"sphere48", {48, 48, 48, 1, 1, 0, 0}, pose_from_axis({40, 100, 48}, {0, 0, 1})},
      {"sphere50", {50, 50, 50, 1, 1, 0, 0}, pose_from_axis({148, 100, 50}, {0, 0, 1})},
      {"sphere52", {52, 52, 52, 1, 1, 0, 0}, pose_from_axis({260, 100, 52}, {0, 0, 1})}};
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
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
  std::vector<sim::ScenePart> parts = {
      {"mallet/head", {30, 30, 56, 0.1, 1.0, 0, 0}, pose_from_axis({60, 240, 30}, x)},
      {"mallet/shaft", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({60, 70, 30}, y, 1.5708)},
      {"lookalike/drum", {30, 30, 56, 0.1, 1.0, 0, 0}, pose_from_axis({250, 60, 30}, y)},
      {"lookalike/rod", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({250, 300, 12}, {1, 0.2, 0})},
      {"hammer/head", {15, 15, 45, 0.1, 1.0, 0, 0}, pose_from_axis({320, 200, 15}, y)},
      {"hammer/shaft", {12, 10, 120, 0.1, 1.0, 0, 0}, pose_from_axis({320, 35, 12}, y)},
      {"occluder/box", {20, 40, 25, 0.1, 0.1, 0, 0}, pose_from_axis({115, 120, 25}, {0, 0, 1})},
      {"occluder/block", {15, 15, 35, 0.1, 0.1, 0, 0}, pose_from_axis({265, -10, 35}, {0, 0, 1})}};
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
