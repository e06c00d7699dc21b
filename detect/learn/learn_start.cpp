#include "detect/learn/learn_start.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rangefit {
namespace {

// Horizontal extents closer than this ratio count as equal (see the turned starts below).
constexpr double kSimilarMoments = 1.25;

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

namespace {

// The frame of the points' moments and their extents in it. On a plane: z along its normal
// towards the object, x and y the horizontal moments' axes, and the part reaching down to it.
struct MomentFrame {
  Eigen::Matrix3d axes;
  Eigen::Vector3d lo, hi;
};

MomentFrame moment_frame(std::span<const Eigen::Vector3d> points,
                         const std::optional<pca::Plane>& plane) {
  MomentFrame f;
  const Eigen::Vector3d c = pca::centroid(points);
  if (plane && plane->valid) {
    const Eigen::Vector3d n = pca::normal_towards(*plane, c);
    Eigen::Matrix3d cov = pca::covariance(points, c);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    const pca::Eigen3 e = pca::eigen_symmetric(P * cov * P);
    f.axes.col(0) = e.vectors.col(2);  // largest horizontal moment
    f.axes.col(1) = n.cross(f.axes.col(0)).normalized();
    f.axes.col(2) = n;
    extents(points, f.axes, f.lo, f.hi);
    f.lo.z() = n.dot(plane->point);  // the part reaches down to the plane
  } else {
    const pca::Eigen3 e = pca::eigen_symmetric(pca::covariance(points, c));
    f.axes = e.vectors;
    if (f.axes.determinant() < 0.0) f.axes.col(0) = -f.axes.col(0);
    extents(points, f.axes, f.lo, f.hi);
  }
  return f;
}

}  // namespace

std::vector<PosedSuperquadric> learn_starts(std::span<const Eigen::Vector3d> points,
                                            const std::optional<pca::Plane>& plane,
                                            std::span<const StartShape> shapes) {
  std::vector<PosedSuperquadric> out;
  if (points.size() < 3) return out;
  const MomentFrame moments = moment_frame(points, plane);
  const Eigen::Matrix3d& axes = moments.axes;
  const Eigen::Vector3d &lo = moments.lo, &hi = moments.hi;
  const bool on_plane = plane && plane->valid;
  const double h0 = hi.x() - lo.x(), h1 = hi.y() - lo.y();
  // The starts of one frame; turned: z along the plane normal only, round sections (untapered
  // unless `tapered`; from there the fit finds the section's shape as well as from any other).
  auto add_frame = [&](const Eigen::Matrix3d& frame, Eigen::Vector3d f_lo, Eigen::Vector3d f_hi,
                       bool turned, bool tapered = false) {
    const Eigen::Vector3d centre = frame * (0.5 * (f_lo + f_hi));
    const Eigen::Vector3d half =
        (0.5 * (f_hi - f_lo)).cwiseMax(1e-3 * (f_hi - f_lo).maxCoeff()).cwiseMax(0.5);
    for (int zi = turned ? 2 : 0; zi < 3; ++zi) {
      const Eigen::Matrix3d R = z_along(frame, zi);
      const double a[3] = {half[(zi + 1) % 3], half[(zi + 2) % 3], half[zi]};
      for (const StartShape& s : shapes) {
        if (s.taper != 0.0 && !(on_plane && zi == 2)) continue;
        if (turned && s.eps2 != 1.0) continue;
        if (turned && !tapered && s.taper != 0.0) continue;
        // A tapered part is widest at one end, 1 + |k| times its mid-height size: that end,
        // not the middle, spans the points.
        const double w = 1.0 / (1.0 + std::abs(s.taper));
        PosedSuperquadric p;
        p.shape = Superquadric{w * a[0], w * a[1], a[2], s.eps1, s.eps2, s.taper, s.taper};
        p.T_world_part.linear() = R;
        p.T_world_part.translation() = centre;
        out.push_back(p);
      }
    }
  };
  add_frame(axes, lo, hi, false);
  // One view of a round or square object standing on the plane shows only its near half: the
  // points span its full width across the line of sight but about half of it along that line,
  // and a start in the middle of what was seen sits half a radius in front of the object's axis.
  // Complete the section to the wider extent on either side of the short axis (the hidden side
  // is one of them), z along the normal, round sections.
  if (on_plane && std::max(h0, h1) >= kSimilarMoments * std::min(h0, h1)) {
    const int s_axis = h0 < h1 ? 0 : 1;
    const double missing = std::abs(h0 - h1);
    for (const double side : {-1.0, 1.0}) {
      Eigen::Vector3d c_lo = lo, c_hi = hi;
      if (side < 0.0) {
        c_lo[s_axis] -= missing;
      } else {
        c_hi[s_axis] += missing;
      }
      add_frame(axes, c_lo, c_hi, true, true);
    }
  }
  // When the object's two horizontal moments are about equal, their axes say little about how
  // its cross-section is turned, and a square-ish section (eps2 away from 1) started 45 deg off
  // ends in a local minimum. Try the frame turned by 45 deg about the normal too.
  if (on_plane && std::max(h0, h1) < kSimilarMoments * std::min(h0, h1)) {
    const Eigen::Matrix3d turned =
        Eigen::AngleAxisd(0.25 * std::numbers::pi, axes.col(2)).toRotationMatrix() * axes;
    Eigen::Vector3d t_lo, t_hi;
    extents(points, turned, t_lo, t_hi);
    t_lo.z() = lo.z();
    add_frame(turned, t_lo, t_hi, true);
  }
  return out;
}

}  // namespace rangefit
