#pragma once
// Principal component analysis of small point sets (thesis eq. 4.1-4.3): centroid, covariance,
// eigenvectors, and the plane fit built from them. Shared by normal estimation, the bore axis
// line fit (largest eigenvector) and the superquadric initialisation.

#include <Eigen/Core>
#include <span>

namespace rangefit::pca {

// Running sums for a covariance, so callers can add points one by one without storing them.
struct Moments {
  double count = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();

  void add(const Eigen::Vector3d& p) {
    count += 1.0;
    sum += p;
    sum_outer.noalias() += p * p.transpose();
  }
  // From ten plain sums over the points: n, x, y, z, xx, xy, xz, yy, yz, zz.
  static Moments from_sums(const double (&s)[10]) {
    Moments m;
    m.count = s[0];
    m.sum = Eigen::Vector3d(s[1], s[2], s[3]);
    m.sum_outer << s[4], s[5], s[6], s[5], s[7], s[8], s[6], s[8], s[9];
    return m;
  }
  Eigen::Vector3d mean() const { return sum / count; }
  // Sample covariance with the 1/(n-1) normalisation of eq. 4.2; zero for fewer than two points.
  Eigen::Matrix3d covariance() const;
};

// Eq. 4.1. Zero for an empty set.
Eigen::Vector3d centroid(std::span<const Eigen::Vector3d> points);

// Eq. 4.2/4.3 about `mean`, normalised by n-1. Zero for fewer than two points.
Eigen::Matrix3d covariance(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& mean);

// Eigen decomposition of a symmetric 3x3 matrix: values ascending, vectors as unit columns.
struct Eigen3 {
  Eigen::Vector3d values = Eigen::Vector3d::Zero();
  Eigen::Matrix3d vectors = Eigen::Matrix3d::Identity();
};
Eigen3 eigen_symmetric(const Eigen::Matrix3d& cov);
// The same by the closed-form solver: ~10x faster, and as accurate for the smallest eigenvector
// when the smallest eigenvalue is well separated (a surface patch: the normal). The iterative
// solver above stays the choice for nearly coincident smallest eigenvalues.
Eigen3 eigen_symmetric_direct(const Eigen::Matrix3d& cov);

// C n = lambda_min n: the normal of a surface patch (sign arbitrary).
Eigen::Vector3d smallest_eigenvector(const Eigen::Matrix3d& cov);
// C v = lambda_max v: the direction of a line-like set, e.g. the bore axis points.
Eigen::Vector3d largest_eigenvector(const Eigen::Matrix3d& cov);

struct Plane {
  bool valid = false;                                 // false: fewer than 3 points or collinear
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // centroid of the fitted points, mm
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, sign arbitrary
  double rms = 0.0;                                   // rms point-to-plane distance, mm
};
// Total least-squares plane through the points (smallest eigenvector of the covariance).
Plane fit_plane(std::span<const Eigen::Vector3d> points);

// The plane's unit normal turned towards `point` (to the side of a table the object is on).
Eigen::Vector3d normal_towards(const Plane& plane, const Eigen::Vector3d& point);

// Line through the points: centroid and largest eigenvector (thesis 4.1.3, axis pose).
struct Line {
  bool valid = false;  // false: fewer than 2 points or all coincident
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};
Line fit_line(std::span<const Eigen::Vector3d> points);

}  // namespace rangefit::pca
