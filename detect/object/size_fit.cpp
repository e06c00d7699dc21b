#include "detect/object/size_fit.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

#include "detect/common/levenberg_marquardt.hpp"
#include "detect/object/point_lanes.hpp"

namespace rangefit {
namespace {

using Vector8d = Eigen::Matrix<double, 8, 1>;
using Matrix8d = Eigen::Matrix<double, 8, 8>;

// A direction the points leave free with at least this component along a scale frees the scale.
constexpr double kFreeComponent = 0.1;
// A round of weights that moves the part (or its size at its largest extent) by less than this
// (mm) is the last.
constexpr double kSettledMm = 1e-3;

struct State {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  double log_across = 0.0, log_along = 0.0;
};

Superquadric scaled(const Superquadric& part, const State& s) {
  Superquadric out = part;
  const double across = std::exp(s.log_across), along = std::exp(s.log_along);
  out.a1 *= across, out.a2 *= across, out.a3 *= along;
  return out;
}

// Per point: 1 / |grad G| (G - 1 to mm) times sqrt(w), fixed for a round.
std::vector<double> round_factors(const Superquadric& part, const State& s,
                                  std::span<const Eigen::Vector3d> points, double cauchy_mm) {
  const SuperquadricMetric m(scaled(part, s));
  const Eigen::Isometry3d inv = s.T.inverse();
  std::vector<double> f(points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector3d grad;
    const double g = m.value_and_gradient(inv * points[i], grad);
    const double norm = grad.norm();
    if (!(norm > 0.0) || !std::isfinite(g)) continue;
    const double d = (g - 1.0) / norm;
    f[i] = std::sqrt(1.0 / (1.0 + (d / cauchy_mm) * (d / cauchy_mm))) / norm;
  }
  return f;
}

State apply(const State& s, const Vector8d& h, double length, double max_log);

// Height of the scaled, posed part's lowest point above the support plane (n, offset), by its
// inscribed ellipsoid: exact for a part resting on a face or along its axis, and smooth (a box's
// or a can's own support has a kink wherever a face or an edge is level, and the LM would stall
// on it).
double support_height(const Superquadric& part, const State& s, const Eigen::Vector4d& plane) {
  const Eigen::Vector3d n = plane.head<3>();
  return n.dot(s.T.translation()) - plane[3] -
         support(ellipsoid_of(scaled(part, s)), s.T.linear().transpose() * -n);
}

// Sums over the points, four at a time: 0.5 r^2, the upper triangle of J^T J row by row (36),
// then J^T r (8). Increments in the part frame, q' = exp(-[w]x) (q - dt): dr/d(dt) = -g,
// dr/dw = g x q; the scales: d/d(log s) of G(q / s) = -q . g over the scaled coordinates, per
// `length` mm of log s x length so that all eight columns are in mm (the free directions are
// found by one threshold). The lanes are added in a fixed order, so the AVX2 and SSE2 builds
// agree bit for bit.
constexpr int kSizeSums = 1 + 36 + 8;
[[gnu::always_inline]] inline void point_sums(const SuperquadricMetric& m,
                                              const Eigen::Matrix3d& Rt, const Eigen::Vector3d& t,
                                              const PointLanes& pts, double length, double* out) {
  using lanes::V4d;
  V4d acc[kSizeSums] = {};
  const double inv_length = 1.0 / length;
  for (std::size_t i = 0; i < pts.blocks; ++i) {
    const WeightedResiduals e = weighted_residuals(m, Rt, t, pts, i);
    const V4d &qx = e.qx, &qy = e.qy, &qz = e.qz, &r = e.r, &gx = e.gx, &gy = e.gy, &gz = e.gz;
    const V4d j[8] = {-gx,
                      -gy,
                      -gz,
                      gy * qz - gz * qy,
                      gz * qx - gx * qz,
                      gx * qy - gy * qx,
                      -(qx * gx + qy * gy) * inv_length,
                      -(qz * gz) * inv_length};
    acc[0] += 0.5 * r * r;
    int k = 1;
    for (int a = 0; a < 8; ++a) {
      for (int b = a; b < 8; ++b) acc[k++] += j[a] * j[b];
    }
    for (int a = 0; a < 8; ++a) acc[k++] += j[a] * r;
  }
  for (int k = 0; k < kSizeSums; ++k) out[k] = ((acc[k][0] + acc[k][1]) + acc[k][2]) + acc[k][3];
}

using PointSumsFn = void (*)(const SuperquadricMetric&, const Eigen::Matrix3d&,
                             const Eigen::Vector3d&, const PointLanes&, double, double*);
void point_sums_sse2(const SuperquadricMetric& m, const Eigen::Matrix3d& Rt,
                     const Eigen::Vector3d& t, const PointLanes& pts, double length, double* out) {
  point_sums(m, Rt, t, pts, length, out);
}
#ifdef RANGEFIT_LANES_AVX2
[[gnu::target("avx2")]] void point_sums_avx2(const SuperquadricMetric& m, const Eigen::Matrix3d& Rt,
                                             const Eigen::Vector3d& t, const PointLanes& pts,
                                             double length, double* out) {
  point_sums(m, Rt, t, pts, length, out);
}
#endif

LmLinearisation<8> linearise_sized(const Superquadric& part, const State& s, const PointLanes& pts,
                                   std::size_t point_count, double length, const SizeFitOptions& o,
                                   bool with_support, const Vector8d& moves) {
#ifdef RANGEFIT_LANES_AVX2
  const PointSumsFn kernel = lanes::cpu_has_avx2() ? point_sums_avx2 : point_sums_sse2;
#else
  const PointSumsFn kernel = point_sums_sse2;
#endif
  double sums[kSizeSums];
  kernel(SuperquadricMetric(scaled(part, s)), s.T.linear().transpose(), s.T.translation(), pts,
         length, sums);
  LmLinearisation<8> lin;
  lin.cost = sums[0];
  const double* sum = sums + 1;
  for (int r = 0; r < 8; ++r) {
    for (int c = r; c < 8; ++c) lin.jtj(r, c) = *sum++ * moves[r] * moves[c];
  }
  for (int r = 0; r < 8; ++r) lin.g[r] = *sum++ * moves[r];
  const double h0 = o.support_plane ? support_height(part, s, *o.support_plane) : 0.0;
  // Outside [-support_below_mm, support_above_mm] the residual is the excess.
  const double excess = h0 < -o.support_below_mm  ? h0 + o.support_below_mm
                        : h0 > o.support_above_mm ? h0 - o.support_above_mm
                                                  : 0.0;
  if (with_support && o.support_plane && excess != 0.0) {
    // One residual for the table, weighted like support_weight x the points, active only where
    // the part sinks past the slack; its Jacobian by forward differences.
    const double w = std::sqrt(o.support_weight * static_cast<double>(point_count));
    Vector8d j;
    constexpr double kStep = 1e-6;
    for (int k = 0; k < 8; ++k) {
      const State nudged = apply(s, kStep * Vector8d::Unit(k), length, o.max_log_scale);
      j[k] = w * (support_height(part, nudged, *o.support_plane) - h0) / kStep;
    }
    j = j.cwiseProduct(moves);
    const double r = w * excess;
    lin.cost += 0.5 * r * r;
    lin.jtj.selfadjointView<Eigen::Upper>().rankUpdate(j);
    lin.g += j * r;
  }
  lin.jtj = lin.jtj.selfadjointView<Eigen::Upper>();
  return lin;
}

State apply(const State& s, const Vector8d& h, double length, double max_log) {
  State out = s;
  out.T.translation() += s.T.linear() * h.head<3>();
  const Eigen::Vector3d w = h.segment<3>(3);
  const double angle = w.norm();
  if (angle > 0.0) {
    out.T.linear() = s.T.linear() * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  }
  out.log_across = std::clamp(s.log_across + h[6] / length, -max_log, max_log);
  out.log_along = std::clamp(s.log_along + h[7] / length, -max_log, max_log);
  return out;
}

}  // namespace

SizeFit fit_size(const Superquadric& part, std::span<const Eigen::Vector3d> points,
                 const Eigen::Isometry3d& initial, const SizeFitOptions& options) {
  SizeFit out;
  out.T_world_part = initial;
  if (!part.valid() || !initial.matrix().allFinite() || points.size() < 9) return out;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) return out;
  }
  State s{initial, 0.0, 0.0};
  const double length = part.max_size();
  LmOptions lm;
  lm.max_iterations = options.iterations;
  // The coordinates the fit moves (1) and holds (0): translation, rotation, the two scales.
  Vector8d moves = Vector8d::Ones();
  if (!options.free_rotation) moves.segment<3>(3).setZero();
  Vector8d pose_only = moves;
  pose_only.tail<2>().setZero();
  if (!options.free_size) moves = pose_only;
  const auto fit = [&](const State& start, const PointLanes& lanes, bool support,
                       const Vector8d& mask) {
    return levenberg_marquardt<8>(
        start, lm,
        [&](const State& x) {
          return linearise_sized(part, x, lanes, points.size(), length, options, support, mask);
        },
        [&](const State& x, const Vector8d& h) {
          return apply(x, h.cwiseProduct(mask), length, options.max_log_scale);
        },
        [&](const State& x) { return x.T.translation().norm() + 1.0; });
  };
  std::vector<double> factor;
  for (int round = 0; round < std::max(1, options.rounds); ++round) {
    factor = round_factors(part, s, points, options.cauchy_mm);
    const State before = s;
    s = fit(s, PointLanes(points, factor), true, moves).x;
    // Settled: the weights would not change.
    const double moved =
        (s.T.translation() - before.T.translation()).norm() +
        length *
            (Eigen::AngleAxisd(before.T.linear().transpose() * s.T.linear()).angle() +
             std::abs(s.log_across - before.log_across) + std::abs(s.log_along - before.log_along));
    if (moved < kSettledMm) break;
  }
  const PointLanes last(points, factor);
  const LmLinearisation<8> lin =
      linearise_sized(part, s, last, points.size(), length, options, true, moves);
  // The model's own size with the pose fitted again from the free fit's (same weights): what
  // the free size gains over it is the size's doing, not a better pose's. At a fixed size the
  // fit is that already.
  const double start_cost =
      options.free_size ? fit(State{s.T, 0.0, 0.0}, last, false, pose_only).lin.cost : lin.cost;
  double weight = 0.0;
  for (double f : factor) weight += f > 0.0 ? 1.0 : 0.0;
  if (weight <= 8.0) return out;
  // s^2 (J^T J)^+: directions the points leave free (a cylinder's spin) get no variance, and a
  // scale that moves with one of them is free.
  const double s2 = 2.0 * lin.cost / (weight - 8.0);
  const Eigen::SelfAdjointEigenSolver<Matrix8d> eig(lin.jtj);
  const Vector8d& lambda = eig.eigenvalues();
  Vector8d inverse = Vector8d::Zero();
  bool free_scale[2] = {false, false};
  for (int i = 0; i < 8; ++i) {
    if (lambda[i] > 1e-9 * lambda[7]) {
      inverse[i] = 1.0 / lambda[i];
      continue;
    }
    for (int k = 0; k < 2; ++k) {
      free_scale[k] = free_scale[k] || std::abs(eig.eigenvectors()(6 + k, i)) > kFreeComponent;
    }
  }
  const Matrix8d cov =
      s2 * eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
  out.ok = true;
  out.T_world_part = s.T;
  out.across = std::exp(s.log_across);
  out.along = std::exp(s.log_along);
  const auto sigma = [&](int k) {
    return cov(k, k) > 0.0 && !free_scale[k - 6] ? std::sqrt(cov(k, k)) / length
                                                 : std::numeric_limits<double>::infinity();
  };
  out.across_sigma = sigma(6);
  out.along_sigma = sigma(7);
  out.rms_mm = std::sqrt(2.0 * lin.cost / weight);
  out.model_rms_mm = std::sqrt(2.0 * start_cost / weight);
  return out;
}

}  // namespace rangefit
