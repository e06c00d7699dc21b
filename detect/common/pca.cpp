#include "detect/common/pca.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace rangefit::pca {

Eigen::Matrix3d Moments::covariance() const {
  if (count < 2.0) return Eigen::Matrix3d::Zero();
  const Eigen::Vector3d m = mean();
  return (sum_outer - count * m * m.transpose()) / (count - 1.0);
}

Eigen::Vector3d centroid(std::span<const Eigen::Vector3d> points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : points) sum += p;
  return points.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(points.size()));
}

Eigen::Matrix3d covariance(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& mean) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  if (points.size() < 2) return c;
  for (const auto& p : points) {
    const Eigen::Vector3d d = p - mean;
    c.noalias() += d * d.transpose();
  }
  return c / static_cast<double>(points.size() - 1);
}

Eigen3 eigen_symmetric(const Eigen::Matrix3d& cov) {
  // The iterative solver: computeDirect loses precision for the flat patches we care about.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  Eigen3 out;
  if (solver.info() != Eigen::Success) return out;
  out.values = solver.eigenvalues();
  out.vectors = solver.eigenvectors();
  return out;
}

Eigen3 eigen_symmetric_direct(const Eigen::Matrix3d& cov) {
  Eigen3 out;
  if (!cov.allFinite()) return out;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(cov);
  out.values = solver.eigenvalues();
  out.vectors = solver.eigenvectors();
  return out;
}

Eigen::Vector3d smallest_eigenvector(const Eigen::Matrix3d& cov) {
  return eigen_symmetric(cov).vectors.col(0);
}

Eigen::Vector3d largest_eigenvector(const Eigen::Matrix3d& cov) {
  return eigen_symmetric(cov).vectors.col(2);
}

Plane fit_plane(std::span<const Eigen::Vector3d> points) {
  Plane plane;
  if (points.size() < 3) return plane;
  plane.point = centroid(points);
  const Eigen3 e = eigen_symmetric(covariance(points, plane.point));
  // Collinear or coincident points leave two eigenvalues near zero: the plane is undefined.
  if (!(e.values(1) > 1e-12 * std::max(1.0, e.values(2)))) return plane;
  plane.normal = e.vectors.col(0);
  const double n = static_cast<double>(points.size());
  plane.rms = std::sqrt(std::max(0.0, e.values(0)) * (n - 1.0) / n);
  plane.valid = true;
  return plane;
}

Eigen::Vector3d normal_towards(const Plane& plane, const Eigen::Vector3d& point) {
  const Eigen::Vector3d n = plane.normal.normalized();
  return n.dot(point - plane.point) < 0.0 ? Eigen::Vector3d(-n) : n;
}

Line fit_line(std::span<const Eigen::Vector3d> points) {
  Line line;
  if (points.size() < 2) return line;
  line.point = centroid(points);
  const Eigen3 e = eigen_symmetric(covariance(points, line.point));
  if (!(e.values(2) > 0.0)) return line;
  line.direction = e.vectors.col(2);
  line.valid = true;
  return line;
}

}  // namespace rangefit::pca
