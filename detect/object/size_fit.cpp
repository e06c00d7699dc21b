#include "detect/object/size_fit.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

#include "detect/common/levenberg_marquardt.hpp"

namespace rangefit {
namespace {

using Vector8d = Eigen::Matrix<double, 8, 1>;
using Matrix8d = Eigen::Matrix<double, 8, 8>;

// A direction the points leave free with at least this component along a scale frees the scale.
constexpr double kFreeComponent = 0.1;

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
// inscribed ellipsoid, whose support along n is sqrt(sum (a_i n.R_i)^2): exact for a part resting
// on a face or along its axis, and smooth (a box's or a can's own support has a kink wherever a
// face or an edge is level, and the LM would stall on it).
double support_height(const Superquadric& part, const State& s, const Eigen::Vector4d& plane) {
  const Eigen::Vector3d n = plane.head<3>();
  const Superquadric sq = scaled(part, s);
  const Eigen::Vector3d m = s.T.linear().transpose() * n;
  const double support = std::sqrt(std::pow(sq.a1 * m.x(), 2) + std::pow(sq.a2 * m.y(), 2) +
                                   std::pow(sq.a3 * m.z(), 2));
  return n.dot(s.T.translation()) - plane[3] - support;
}

LmLinearisation<8> linearise(const Superquadric& part, const State& s,
                             std::span<const Eigen::Vector3d> points,
                             const std::vector<double>& factor, double length,
                             const SizeFitOptions& o, bool with_support, bool free_scales = true) {
  const SuperquadricMetric m(scaled(part, s));
  const Eigen::Isometry3d inv = s.T.inverse();
  LmLinearisation<8> lin;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (factor[i] == 0.0) continue;
    const Eigen::Vector3d q = inv * points[i];
    Eigen::Vector3d g;
    const double r = (m.value_and_gradient(q, g) - 1.0) * factor[i];
    g *= factor[i];
    // Increments in the part frame, q' = exp(-[w]x) (q - dt): dr/d(dt) = -g, dr/dw = g x q;
    // the scales: d/d(log s) of G(q / s) = -q . g over the scaled coordinates, per `length` mm
    // of log s x length so that all eight columns are in mm (the free directions are found by
    // one threshold).
    Vector8d j;
    j << -g, g.cross(q), -(q.x() * g.x() + q.y() * g.y()) / length, -q.z() * g.z() / length;
    if (!free_scales) j.tail<2>().setZero();
    lin.cost += 0.5 * r * r;
    lin.jtj.selfadjointView<Eigen::Upper>().rankUpdate(j);
    lin.g += j * r;
  }
  const double h0 = o.support_plane ? support_height(part, s, *o.support_plane) : 0.0;
  // Outside [-support_below_mm, support_above_mm] the residual is the excess.
  const double excess = h0 < -o.support_below_mm  ? h0 + o.support_below_mm
                        : h0 > o.support_above_mm ? h0 - o.support_above_mm
                                                  : 0.0;
  if (with_support && o.support_plane && excess != 0.0) {
    // One residual for the table, weighted like support_weight x the points, active only where
    // the part sinks past the slack; its Jacobian by forward differences.
    const double w = std::sqrt(o.support_weight * static_cast<double>(points.size()));
    Vector8d j;
    constexpr double kStep = 1e-6;
    for (int k = 0; k < 8; ++k) {
      const State nudged = apply(s, kStep * Vector8d::Unit(k), length, o.max_log_scale);
      j[k] = w * (support_height(part, nudged, *o.support_plane) - h0) / kStep;
    }
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
  std::vector<double> factor;
  for (int round = 0; round < std::max(1, options.rounds); ++round) {
    factor = round_factors(part, s, points, options.cauchy_mm);
    const auto outcome = levenberg_marquardt<8>(
        s, lm,
        [&](const State& x) {
          return linearise(part, x, points, factor, length, options, true, options.free_size);
        },
        [&](const State& x, const Vector8d& h) {
          Vector8d step = h;
          if (!options.free_size) step.tail<2>().setZero();
          return apply(x, step, length, options.max_log_scale);
        },
        [&](const State& x) { return x.T.translation().norm() + 1.0; });
    s = outcome.x;
  }
  const LmLinearisation<8> lin = linearise(part, s, points, factor, length, options, true);
  // The model's own size with the pose fitted again from the free fit's (same weights): what
  // the free size gains over it is the size's doing, not a better pose's.
  const auto at_model = levenberg_marquardt<8>(
      State{s.T, 0.0, 0.0}, lm,
      [&](const State& x) {
        return linearise(part, x, points, factor, length, options, false, false);
      },
      [&](const State& x, const Vector8d& h) {
        Vector8d pose_only = h;
        pose_only.tail<2>().setZero();
        return apply(x, pose_only, length, options.max_log_scale);
      },
      [&](const State& x) { return x.T.translation().norm() + 1.0; });
  const double start_cost = at_model.lin.cost;
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
