#include "detect/learn_start.hpp"

#include <algorithm>
#include <limits>

namespace rangefit {
namespace {

// Half ranges and centre of the points along the three (unit, orthogonal) columns of `axes`.
void extents(std::span<const Eigen::Vector3d> points, const Eigen::Matrix3d& axes,
             Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  lo.setConstant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d u = axes.transpose() * p;
    lo = lo.cwiseMin(u);
    hi = hi.cwiseMax(u);
  }
}

// The frame `axes` (columns) with z along column zi, right-handed.
Eigen::Matrix3d z_along(const Eigen::Matrix3d& axes, int zi) {
  Eigen::Matrix3d R;
  R.col(2) = axes.col(zi);
  R.col(0) = axes.col((zi + 1) % 3);
  R.col(1) = R.col(2).cross(R.col(0));
  return R;
}

}  // namespace

std::vector<PosedSuperquadric> learn_starts(std::span<const Eigen::Vector3d> points,
                                            const std::optional<pca::Plane>& plane,
                                            std::span<const StartShape> shapes) {
  std::vector<PosedSuperquadric> out;
  if (points.size() < 3) return out;
  const Eigen::Vector3d c = pca::centroid(points);
  Eigen::Matrix3d axes;
  Eigen::Vector3d lo, hi, centre, half;
  if (plane && plane->valid) {
    // Normal towards the object; horizontal axes from the moments of the projected points.
    Eigen::Vector3d n = plane->normal.normalized();
    if (n.dot(c - plane->point) < 0.0) n = -n;
    Eigen::Matrix3d cov = pca::covariance(points, c);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    const pca::Eigen3 e = pca::eigen_symmetric(P * cov * P);
    axes.col(0) = e.vectors.col(2);  // largest horizontal moment
    axes.col(1) = n.cross(axes.col(0)).normalized();
    axes.col(2) = n;
    extents(points, axes, lo, hi);
    lo.z() = n.dot(plane->point);  // the part reaches down to the plane
  } else {
    const pca::Eigen3 e = pca::eigen_symmetric(pca::covariance(points, c));
    axes = e.vectors;
    if (axes.determinant() < 0.0) axes.col(0) = -axes.col(0);
    extents(points, axes, lo, hi);
  }
  centre = axes * (0.5 * (lo + hi));
  half = (0.5 * (hi - lo)).cwiseMax(1e-3 * (hi - lo).maxCoeff()).cwiseMax(0.5);
  const bool on_plane = plane && plane->valid;
  for (int zi = 0; zi < 3; ++zi) {
    const Eigen::Matrix3d R = z_along(axes, zi);
    const double a[3] = {half[(zi + 1) % 3], half[(zi + 2) % 3], half[zi]};
    for (const StartShape& s : shapes) {
      if (s.taper != 0.0 && !(on_plane && zi == 2)) continue;
      PosedSuperquadric p;
      p.shape = Superquadric{a[0], a[1], a[2], s.eps1, s.eps2, s.taper, s.taper};
      p.T_world_part.linear() = R;
      p.T_world_part.translation() = centre;
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace rangefit
