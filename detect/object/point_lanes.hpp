#pragma once
// Points in lanes of four (structure of arrays) with a weight each, for the vectorised fits
// (pose_fit.cpp, size_fit.cpp), and the step every such kernel starts with: four points moved
// into the part frame, G - 1 and its gradient there, both times the weights.

#include <Eigen/Core>
#include <cstring>
#include <span>
#include <vector>

#include "detect/object/superquadric_eval.hpp"

namespace rangefit {

// The tail is padded with copies of the last point at weight 0. Plain doubles, loaded with
// memcpy (unaligned loads).
struct PointLanes {
  std::vector<double> x, y, z, w;
  std::size_t blocks = 0;

  // Every point at weight 1.
  explicit PointLanes(std::span<const Eigen::Vector3d> points) {
    for (const Eigen::Vector3d& p : points) add(p, 1.0);
    pad();
  }
  // Each point at its weight; points of weight 0 are left out.
  PointLanes(std::span<const Eigen::Vector3d> points, std::span<const double> weights) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (weights[i] != 0.0) add(points[i], weights[i]);
    }
    pad();
  }

  [[gnu::always_inline]] static lanes::V4d load(const std::vector<double>& v, std::size_t block) {
    lanes::V4d out;
    std::memcpy(&out, v.data() + 4 * block, sizeof out);
    return out;
  }

 private:
  void add(const Eigen::Vector3d& p, double weight) {
    x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z()), w.push_back(weight);
  }
  void pad() {
    blocks = (x.size() + 3) / 4;
    while (!x.empty() && x.size() < 4 * blocks) add({x.back(), y.back(), z.back()}, 0.0);
  }
};

// Block i of the points in the part frame, q = R^T (p - t), with r = w (G(q) - 1) and
// g = w grad G(q).
struct WeightedResiduals {
  lanes::V4d qx, qy, qz, r, gx, gy, gz;
};

[[gnu::always_inline]] inline WeightedResiduals weighted_residuals(const SuperquadricMetric& m,
                                                                   const Eigen::Matrix3d& Rt,
                                                                   const Eigen::Vector3d& t,
                                                                   const PointLanes& pts,
                                                                   std::size_t i) {
  using lanes::V4d;
  WeightedResiduals o;
  const V4d px = PointLanes::load(pts.x, i) - t.x(), py = PointLanes::load(pts.y, i) - t.y(),
            pz = PointLanes::load(pts.z, i) - t.z();
  o.qx = Rt(0, 0) * px + Rt(0, 1) * py + Rt(0, 2) * pz;
  o.qy = Rt(1, 0) * px + Rt(1, 1) * py + Rt(1, 2) * pz;
  o.qz = Rt(2, 0) * px + Rt(2, 1) * py + Rt(2, 2) * pz;
  const V4d w = PointLanes::load(pts.w, i);
  o.r = (m.evaluate<V4d, true>(o.qx, o.qy, o.qz, &o.gx, &o.gy, &o.gz) - 1.0) * w;
  o.gx *= w;
  o.gy *= w;
  o.gz *= w;
  return o;
}

}  // namespace rangefit
