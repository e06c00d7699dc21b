#pragma once
// Teach-in scans for the model-learning tests and benchmark: one object alone on the table,
// seen by the pinhole renderer from the front (one view) and from behind (the second view, in
// the same world frame), and the error of a learnt part against the truth with the learnt axes
// matched to the true ones (a superquadric has several parametrisations of the same shape: a box
// may put z along any edge, a cylinder swap x and y, a flipped z negates the taper).

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "detect/common/point_cloud.hpp"
#include "sim/scene_objects.hpp"
#include "sim/superquadric_raycast.hpp"

namespace rangefit::test {

inline constexpr double kObjectX = 150.0, kObjectY = 100.0;  // where the object stands

// The object's view from the front (view 0) or from behind (view 1), at a quarter of the
// thesis table view's 440 x 330 rays.
inline sim::SceneView teach_view(int view, double noise_sigma = 0.0, std::uint64_t seed = 1) {
  sim::SceneView v;
  v.fov_deg = 36.0;
  v.width = 220;
  v.height = 165;
  v.target = {kObjectX, kObjectY, 20.0};
  v.eye = view == 0 ? Eigen::Vector3d(kObjectX, kObjectY - 350.0, 430.0)
                    : Eigen::Vector3d(kObjectX + 60.0, kObjectY + 350.0, 430.0);
  v.table_min = {kObjectX - 200.0, kObjectY - 160.0};
  v.table_max = {kObjectX + 200.0, kObjectY + 160.0};
  v.noise_sigma_mm = noise_sigma;
  v.noise_seed = seed + static_cast<std::uint64_t>(view) * 7919;
  return v;
}

// The points of `views` (0, or 0 and 1) of the parts, fused: all in the table frame.
inline std::vector<Eigen::Vector3d> teach_scan(const std::vector<sim::ScenePart>& parts, int views,
                                               double noise_sigma = 0.0, std::uint64_t seed = 1) {
  std::vector<Eigen::Vector3d> out;
  for (int v = 0; v < views; ++v) {
    const sim::RenderedScene s = sim::render_scene(parts, teach_view(v, noise_sigma, seed));
    out.insert(out.end(), s.cloud.points.begin(), s.cloud.points.end());
  }
  return out;
}

// A thesis part (or any) resting on the table at the object position, yaw and face drawn.
inline std::vector<sim::ScenePart> resting(const Superquadric& sq, std::uint64_t seed,
                                           double p_standing = 0.5) {
  std::mt19937_64 rng(seed);
  sim::TableObject o = sim::resting_part("target", sq, sim::rest_of(sq), rng, p_standing);
  std::uniform_real_distribution<double> yaw(0.0, 6.283185307179586);
  sim::place(o, kObjectX, kObjectY, yaw(rng));
  return o.parts;
}

// A random superquadric: half sizes 20-60 mm, eps 0.1-1.9, taper -0.5..0.5 (both, or none).
inline Superquadric random_superquadric(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> a(20.0, 60.0), e(0.1, 1.9), k(-0.5, 0.5);
  Superquadric s;
  s.a1 = a(rng), s.a2 = a(rng), s.a3 = a(rng);
  s.eps1 = e(rng), s.eps2 = e(rng);
  s.kx = k(rng), s.ky = k(rng);
  return s;
}

struct ShapeError {
  double size = 0.0;   // largest relative size error over the three axes
  double shape = 0.0;  // largest absolute error of eps1, eps2, kx, ky
  bool axes_matched = true;
};

// Learnt part vs the truth, each with its pose: learnt axis i is matched to the true axis it is
// most parallel to.
inline ShapeError shape_error(const Superquadric& l, const Eigen::Isometry3d& T_l,
                              const Superquadric& t, const Eigen::Isometry3d& T_t) {
  ShapeError e;
  const double la[3] = {l.a1, l.a2, l.a3}, ta[3] = {t.a1, t.a2, t.a3};
  std::array<int, 3> perm{};
  std::array<double, 3> sign{};
  for (int i = 0; i < 3; ++i) {
    double best = -1.0;
    for (int j = 0; j < 3; ++j) {
      const double d = T_l.linear().col(i).dot(T_t.linear().col(j));
      if (std::abs(d) > best) best = std::abs(d), perm[i] = j, sign[i] = d < 0 ? -1.0 : 1.0;
    }
  }
  if (perm[0] == perm[1] || perm[1] == perm[2] || perm[0] == perm[2]) {
    e.axes_matched = false;
    perm = {0, 1, 2};
    sign = {1.0, 1.0, 1.0};
  }
  for (int i = 0; i < 3; ++i)
    e.size = std::max(e.size, std::abs(la[i] - ta[perm[i]]) / ta[perm[i]]);
  if (perm[2] == 2) {
    const double tk[2] = {t.kx, t.ky};
    e.shape =
        std::max({std::abs(l.eps1 - t.eps1), std::abs(l.eps2 - t.eps2),
                  std::abs(sign[2] * l.kx - tk[perm[0]]), std::abs(sign[2] * l.ky - tk[perm[1]])});
  } else {
    // z along another true axis: the same shape only for eps1 = eps2 (F symmetric in x, y, z)
    // and no taper; otherwise the learnt shape is compared as it stands.
    e.shape = std::max({std::abs(l.eps1 - t.eps1), std::abs(l.eps2 - t.eps1),
                        std::abs(l.eps1 - t.eps2), std::abs(l.kx - t.kx), std::abs(l.ky - t.ky)});
  }
  return e;
}

}  // namespace rangefit::test
