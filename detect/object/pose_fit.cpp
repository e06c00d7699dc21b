#include "detect/object/pose_fit.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "detect/common/levenberg_marquardt.hpp"
#include "detect/common/pca.hpp"
#include "detect/object/point_lanes.hpp"

namespace rangefit {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Cost 0.5 sum r^2 (eq. 2.49), the Gauss-Newton matrix J^T J and the gradient g = J^T r for the
// increment [dt (world), w (part frame)] about T.
using Linearisation = LmLinearisation<6>;

// Sums per point, in the part frame (dt of the increment in the part frame, where dq/d(dt) =
// -I): 0.5 r^2, the upper triangle of J^T J row by row (21), then J^T r (6). Four points at a
// time; the lanes are added in a fixed order, so the AVX2 and SSE2 builds agree bit for bit.
constexpr int kSums = 28;
[[gnu::always_inline]] inline void linearise_lanes(const SuperquadricMetric& m,
                                                   const Eigen::Matrix3d& Rt,
                                                   const Eigen::Vector3d& t, const PointLanes& pts,
                                                   double* out) {
  using lanes::V4d;
  V4d acc[kSums] = {};
  for (std::size_t i = 0; i < pts.blocks; ++i) {
    const WeightedResiduals e = weighted_residuals(m, Rt, t, pts, i);
    const V4d &qx = e.qx, &qy = e.qy, &qz = e.qz, &r = e.r, &gx = e.gx, &gy = e.gy, &gz = e.gz;
    // q = exp(-[w]x) (R^T (p - t) - dt): dr/d(dt) = -grad^T, dr/dw = (grad x q)^T.
    const V4d j[6] = {-gx, -gy, -gz, gy * qz - gz * qy, gz * qx - gx * qz, gx * qy - gy * qx};
    acc[0] += 0.5 * r * r;
    int k = 1;
    for (int a = 0; a < 6; ++a) {
      for (int b = a; b < 6; ++b) acc[k++] += j[a] * j[b];
    }
    for (int a = 0; a < 6; ++a) acc[k++] += j[a] * r;
  }
  for (int k = 0; k < kSums; ++k) out[k] = ((acc[k][0] + acc[k][1]) + acc[k][2]) + acc[k][3];
}

using LineariseFn = void (*)(const SuperquadricMetric&, const Eigen::Matrix3d&,
                             const Eigen::Vector3d&, const PointLanes&, double*);
void linearise_sse2(const SuperquadricMetric& m, const Eigen::Matrix3d& Rt,
                    const Eigen::Vector3d& t, const PointLanes& pts, double* out) {
  linearise_lanes(m, Rt, t, pts, out);
}
#ifdef RANGEFIT_LANES_AVX2
[[gnu::target("avx2")]] void linearise_avx2(const SuperquadricMetric& m, const Eigen::Matrix3d& Rt,
                                            const Eigen::Vector3d& t, const PointLanes& pts,
                                            double* out) {
  linearise_lanes(m, Rt, t, pts, out);
}
#endif

Linearisation linearise(const SuperquadricMetric& m, const Eigen::Isometry3d& T,
                        const PointLanes& pts) {
#ifdef RANGEFIT_LANES_AVX2
  const LineariseFn kernel = lanes::cpu_has_avx2() ? linearise_avx2 : linearise_sse2;
#else
  const LineariseFn kernel = linearise_sse2;
#endif
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Matrix3d Rt = R.transpose();
  double sums[kSums];
  kernel(m, Rt, T.translation(), pts, sums);
  Linearisation lin;
  lin.cost = sums[0];
  Matrix6d& a = lin.jtj;
  int k = 1;
  for (int r = 0; r < 6; ++r) {
    for (int c = r; c < 6; ++c) a(r, c) = a(c, r) = sums[k++];
  }
  for (int r = 0; r < 6; ++r) lin.g[r] = sums[k++];
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

// The pseudo-inverse: J^T J is singular along a symmetric part's free directions (a cylinder's
// spin, every turn of a sphere), which move none of its surface and so no quantity of it either;
// they get variance 0 rather than an undefined one. Eigenvalues below 1e-9 of the largest are
// those (numerically ~1e-16); a direction the points determine only poorly keeps its large
// variance.
Eigen::Matrix<double, 6, 6> PoseFitResult::covariance() const {
  if (points <= 6 || !ok()) return Matrix6d::Zero();
  const double s2 = measure * measure * static_cast<double>(points) / static_cast<double>(points - 6);
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(jtj);
  const Vector6d& lambda = eig.eigenvalues();  // ascending
  Vector6d inverse = Vector6d::Zero();
  for (int i = 0; i < 6; ++i) {
    if (lambda[i] > 1e-9 * lambda[5]) inverse[i] = 1.0 / lambda[i];
  }
  return s2 * eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
}

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
  const PointLanes soa(points);
  const LmOptions lm{options.max_iterations, options.tau, options.gradient_tolerance,
                     options.step_tolerance};
  const auto out = levenberg_marquardt<6>(
      initial, lm, [&](const Eigen::Isometry3d& T) { return linearise(m, T, soa); }, apply_step,
      [](const Eigen::Isometry3d& T) { return T.translation().norm(); });
  const double n = static_cast<double>(points.size());
  result.initial_measure = std::sqrt(2.0 * out.initial_cost / n);
  switch (out.stop) {
    case LmStop::kGradient:
      result.termination = FitTermination::kGradient;
      break;
    case LmStop::kStep:
      result.termination = FitTermination::kStep;
      break;
    case LmStop::kMaxIterations:
      result.termination = FitTermination::kMaxIterations;
      break;
  }
  result.iterations = out.iterations;
  result.T_world_part = out.x;
  result.measure = std::sqrt(2.0 * out.lin.cost / n);
  result.jtj = out.lin.jtj;
  result.points = points.size();
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
  bool best_preferred = false;
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
      if (init.settle) T = init.settle(T, normal);
      const PoseFitResult r = fit_pose(sq, points, T, short_options);
      if (!r.ok() || !std::isfinite(r.measure) ||
          (init.admissible && !init.admissible(r.T_world_part))) {
        continue;
      }
      const bool preferred = !init.preferred || init.preferred(r.T_world_part);
      if (preferred > best_preferred || (preferred == best_preferred && r.measure < best.measure)) {
        best = r;
        best_preferred = preferred;
      }
    }
  }
  if (!std::isfinite(best.measure)) return best;
  PoseFitOptions full = options;
  full.max_iterations = init.full_iterations;
  return fit_pose(sq, points, best.T_world_part, full);
}

}  // namespace rangefit
