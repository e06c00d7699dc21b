#include "render/view.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rangefit::render {

OrthoView look_from(const Eigen::Vector3d& toward, const Eigen::Vector3d& up_hint) {
  OrthoView v;
  v.toward = toward.normalized();
  Eigen::Vector3d up = up_hint - up_hint.dot(v.toward) * v.toward;
  if (up.norm() < 1e-6 * std::max(1.0, up_hint.norm())) {
    // Looking along the hint: world y is up (x when looking along y).
    const Eigen::Vector3d axis =
        std::abs(v.toward.y()) < 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    up = axis - axis.dot(v.toward) * v.toward;
  }
  v.up = up.normalized();
  v.right = v.up.cross(v.toward);
  return v;
}

namespace {

// The value with `share` of xs below it (xs reordered).
double quantile(std::vector<double>& xs, double share) {
  const auto k = static_cast<std::ptrdiff_t>(share * static_cast<double>(xs.size() - 1) + 0.5);
  std::nth_element(xs.begin(), xs.begin() + k, xs.end());
  return xs[static_cast<std::size_t>(k)];
}

}  // namespace

void fit_to(OrthoView& view, std::span<const Eigen::Vector3d> points, int width, int height,
            double margin, double trim) {
  view.width = std::max(1, width);
  view.height = std::max(1, height);
  std::vector<double> rs, us;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    rs.push_back(p.dot(view.right));
    us.push_back(p.dot(view.up));
    mean += p;
  }
  if (rs.empty()) {
    view.centre.setZero();
    view.px_per_mm = 1.0;
    return;
  }
  mean /= static_cast<double>(rs.size());
  trim = std::clamp(trim, 0.0, 0.25);
  const double lo_r = quantile(rs, trim), hi_r = quantile(rs, 1.0 - trim);
  const double lo_u = quantile(us, trim), hi_u = quantile(us, 1.0 - trim);
  // The centre keeps the points' mean depth, so depth() stays small numbers around the scene.
  const double depth = mean.dot(view.toward);
  view.centre =
      0.5 * (lo_r + hi_r) * view.right + 0.5 * (lo_u + hi_u) * view.up + depth * view.toward;
  const double usable = std::max(0.1, 1.0 - 2.0 * margin);
  const double span_r = std::max(hi_r - lo_r, 1e-3), span_u = std::max(hi_u - lo_u, 1e-3);
  view.px_per_mm = usable * std::min(view.width / span_r, view.height / span_u);
}

}  // namespace rangefit::render
