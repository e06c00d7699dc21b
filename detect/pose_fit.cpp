#include "detect/pose_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "detect/pca.hpp"

namespace rangefit {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Cost 0.5 sum r^2 (eq. 2.49), the Gauss-Newton matrix J^T J and the gradient g = J^T r for the
// increment [dt (world), w (part frame)] about T.
struct Linearisation {
  double cost = 0.0;
  Matrix6d jtj = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
};

Linearisation linearise(const SuperquadricMetric& m, const Eigen::Isometry3d& T,
                        std::span<const Eigen::Vector3d> points) {
  // Accumulated for the increment with dt in the part frame, where dq/d(dt) = -I, then turned
  // into the world-frame dt once: J_world = J_part diag(R^T, I). Only the upper triangle of
  // J^T J is summed per point (21 products instead of 36).
  Linearisation lin;
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Matrix3d Rt = R.transpose();
  const Eigen::Vector3d t = T.translation();
  Eigen::Vector3d grad;
  Vector6d j;
  Matrix6d& a = lin.jtj;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = Rt * (p - t);
    const double r = m.value_and_gradient(q, grad) - 1.0;
    // q = exp(-[w]x) (R^T (p - t) - dt): dr/d(dt) = -grad^T, dr/dw = (grad x q)^T.
    j.head<3>() = -grad;
    j.tail<3>() = grad.cross(q);
    lin.cost += 0.5 * r * r;
    for (int c = 0; c < 6; ++c) {
      for (int k = 0; k <= c; ++k) a(k, c) += j[k] * j[c];
    }
    lin.g += j * r;
  }
  a.triangularView<Eigen::StrictlyLower>() = a.transpose();
  // Back to the world-frame translation increment: B = diag(R, I), A <- B A B^T, g <- B g.
  a.topLeftCorner<3, 3>() = R * a.topLeftCorner<3, 3>() * Rt;
  a.topRightCorner<3, 3>() = R * a.topRightCorner<3, 3>();
  a.bottomLeftCorner<3, 3>() = a.topRightCorner<3, 3>().transpose();
  lin.g.head<3>() = R * lin.g.head<3>();
  return lin;
}

double cost_of(const SuperquadricMetric& m, const Eigen::Isometry3d& T,
               std::span<const Eigen::Vector3d> points) {
  const Eigen::Isometry3d inv = T.inverse();
  double c = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const double r = m.value(inv * p) - 1.0;
    c += 0.5 * r * r;
  }
  return c;
}

Eigen::Isometry3d apply_step(const Eigen::Isometry3d& T, const Vector6d& h) {
  Eigen::Isometry3d out = T;
  out.translation() += h.head<3>();
  const Eigen::Vector3d w = h.tail<3>();
  const double angle = w.norm();
  if (angle > 0.0) {
    out.linear() = T.linear() * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  }
  return out;
}

bool finite_points(std::span<const Eigen::Vector3d> points) {
  return std::all_of(points.begin(), points.end(),
                     [](const Eigen::Vector3d& p) { return p.allFinite(); });
}

}  // namespace

double measure_of_fit(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                      std::span<const Eigen::Vector3d> points) {
  if (points.empty()) return 0.0;
  const double c = cost_of(SuperquadricMetric(sq), T_world_part, points);
  return std::sqrt(2.0 * c / static_cast<double>(points.size()));
}

PoseFitResult fit_pose(const Superquadric& sq, std::span<const Eigen::Vector3d> points,
                       const Eigen::Isometry3d& initial, const PoseFitOptions& options) {
  PoseFitResult result;
  result.T_world_part = initial;
  if (!sq.valid() || !initial.matrix().allFinite() || !finite_points(points)) return result;
  if (points.size() < 6) {
    result.termination = FitTermination::kTooFewPoints;
    return result;
  }
  const SuperquadricMetric m(sq);
  Eigen::Isometry3d T = initial;
  Linearisation lin = linearise(m, T, points);
  double mu = options.tau * lin.jtj.diagonal().maxCoeff();  // eq. 2.60
  if (!(mu > 0.0)) mu = options.tau;
  double nu = 2.0;
  result.termination = FitTermination::kMaxIterations;
  int k = 0;
  for (; k < options.max_iterations; ++k) {
    if (lin.g.lpNorm<Eigen::Infinity>() <= options.gradient_tolerance) {  // eq. 2.63
      result.termination = FitTermination::kGradient;
      break;
    }
    Matrix6d a = lin.jtj;
    a.diagonal().array() += mu;
    const Vector6d h = a.ldlt().solve(-lin.g);  // eq. 2.58
    const double x_norm = T.translation().norm();
    if (!h.allFinite() ||
        h.norm() <= options.step_tolerance * (x_norm + options.step_tolerance)) {  // eq. 2.64
      result.termination = FitTermination::kStep;
      break;
    }
    const Eigen::Isometry3d T_new = apply_step(T, h);
    Linearisation lin_new = linearise(m, T_new, points);
    const double predicted = 0.5 * h.dot(mu * h - lin.g);      // eq. 2.62
    const double rho = (lin.cost - lin_new.cost) / predicted;  // eq. 2.61
    if (predicted > 0.0 && rho > 0.0 && std::isfinite(lin_new.cost)) {
      T = T_new;
      lin = lin_new;
      mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
    } else {
      mu *= nu;
      nu *= 2.0;
    }
  }
  result.iterations = k;
  result.T_world_part = T;
  result.measure = std::sqrt(2.0 * lin.cost / static_cast<double>(points.size()));
  return result;
}

PoseFitResult fit_pose_from_moments(const Superquadric& sq, std::span<const Eigen::Vector3d> points,
                                    const MomentInitOptions& init, const PoseFitOptions& options) {
  PoseFitResult best;
  if (!sq.valid() || !finite_points(points)) return best;
  if (points.size() < 6) {
    best.termination = FitTermination::kTooFewPoints;
    return best;
  }
  const Eigen::Vector3d c = pca::centroid(points);
  const pca::Eigen3 e = pca::eigen_symmetric(pca::covariance(points, c));
  Eigen::Vector3d normal = e.vectors.col(0);  // smallest moment: the patch normal
  const double sizes[3] = {sq.a1, sq.a2, sq.a3};
  PoseFitOptions short_options = options;
  short_options.max_iterations = init.short_iterations;
  int signs = 2;
  if (init.viewpoint) {
    if (normal.dot(*init.viewpoint - c) < 0.0) normal = -normal;  // towards the sensor
    signs = 1;
  }
  best.measure = std::numeric_limits<double>::infinity();
  for (int zi = 0; zi < 3; ++zi) {
    // z along moment direction zi, x along the next one; the centre sits behind the patch by the
    // size of the part along whichever axis the normal became.
    Eigen::Matrix3d R;
    R.col(2) = e.vectors.col(zi);
    R.col(0) = e.vectors.col((zi + 1) % 3);
    R.col(1) = R.col(2).cross(R.col(0));
    const int normal_axis = zi == 0 ? 2 : ((zi + 1) % 3 == 0 ? 0 : 1);
    const double depth = sizes[normal_axis];
    for (int s = 0; s < signs; ++s) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = R;
      T.translation() = c - (s == 0 ? 1.0 : -1.0) * depth * normal;
      const PoseFitResult r = fit_pose(sq, points, T, short_options);
      if (r.ok() && r.measure < best.measure) best = r;
    }
  }
  if (!std::isfinite(best.measure)) return best;
  PoseFitOptions full = options;
  full.max_iterations = init.full_iterations;
  return fit_pose(sq, points, best.T_world_part, full);
}

}  // namespace rangefit
