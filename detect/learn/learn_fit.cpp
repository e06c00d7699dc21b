#include "detect/learn/learn_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "detect/common/levenberg_marquardt.hpp"
#include "detect/learn/learn_surface.hpp"

namespace rangefit {
namespace {

constexpr int kN = 13;  // [dt (world, mm), w (part frame, rad), log a1..a3, eps1, eps2, kx, ky]
constexpr int kModel = 7;
using Vector = Eigen::Matrix<double, kN, 1>;
using Lin = LmLinearisation<kN>;

// Model parameter j of the part (log sizes, then eps and taper).
double get(const Superquadric& s, int j) {
  switch (j) {
    case 0:
      return std::log(s.a1);
    case 1:
      return std::log(s.a2);
    case 2:
      return std::log(s.a3);
    case 3:
      return s.eps1;
    case 4:
      return s.eps2;
    case 5:
      return s.kx;
    default:
      return s.ky;
  }
}

Superquadric clamp(Superquadric s, const ShapeFitOptions& o) {
  s.a1 = std::max(s.a1, o.min_size_mm);
  s.a2 = std::max(s.a2, o.min_size_mm);
  s.a3 = std::max(s.a3, o.min_size_mm);
  s.eps1 = std::clamp(s.eps1, o.min_eps, o.max_eps);
  s.eps2 = std::clamp(s.eps2, o.min_eps, o.max_eps);
  s.kx = std::clamp(s.kx, -o.max_taper, o.max_taper);
  s.ky = std::clamp(s.ky, -o.max_taper, o.max_taper);
  return s;
}

Superquadric set(Superquadric s, int j, double v, const ShapeFitOptions& o) {
  switch (j) {
    case 0:
      s.a1 = std::exp(v);
      break;
    case 1:
      s.a2 = std::exp(v);
      break;
    case 2:
      s.a3 = std::exp(v);
      break;
    case 3:
      s.eps1 = v;
      break;
    case 4:
      s.eps2 = v;
      break;
    case 5:
      s.kx = v;
      break;
    default:
      s.ky = v;
      break;
  }
  return clamp(s, o);
}

double volume_factor(const Superquadric& s, const ShapeFitOptions& o) {
  return std::sqrt(1.0 + o.volume_weight * s.a1 * s.a2 * s.a3 / o.reference_volume);
}

// The residual of one point from G(q) and dG/dq (FitResidual), with its gradient in q. `scale`
// is the distance's 1 / |df/dq| (learn_surface.hpp), 1 for the others.
struct PointResidual {
  double r = 0.0, scale = 1.0;
  Eigen::Vector3d dr_dq = Eigen::Vector3d::Zero();
};
PointResidual point_residual(double g, const Eigen::Vector3d& dg_dq, const Eigen::Vector3d& q,
                             FitResidual kind) {
  if (kind == FitResidual::kMetric) return {g - 1.0, 1.0, dg_dq};
  const RadialDistance d = radial_distance(g, dg_dq, q);
  const double scale = kind == FitResidual::kDistance ? d.normalising() : 1.0;
  return {d.f * scale, scale, d.df_dq * scale};
}

// The same point's residual for a nudged model (a Jacobian column by differences), from the
// nudged G, with the distance's scale of the current model. Holding that factor fixed within
// one linearisation (as iteratively reweighted least squares does) leaves the point's distance
// as the quantity minimised, at no second gradient per nudge.
double nudged_residual(double g, double q_norm, double scale, FitResidual kind) {
  return kind == FitResidual::kMetric ? g - 1.0 : scale * radial_distance(g, q_norm);
}

// The point of the part farthest along `u` (unit, part frame): where the normal of the untapered
// superquadric (eq. 2.14) is parallel to u, then tapered as every surface point is. Exact for an
// untapered part and, whatever the taper, for u along its z-axis (its end).
Eigen::Vector3d extreme_point(const Superquadric& s, const Eigen::Vector3d& u) {
  const double uxy = std::hypot(u.x(), u.y());
  // Longitude: tan^(2 - eps2) omega = a2 u2 / (a1 u1).
  // (eps 2 has a flat normal map, pinched edges: the exponent is kept finite just below it.)
  const double pw = 1.0 / (2.0 - std::min(s.eps2, 1.95)), pe = 1.0 / (2.0 - std::min(s.eps1, 1.95));
  const double omega = std::atan2(std::copysign(std::pow(std::abs(s.a2 * u.y()), pw), u.y()),
                                  std::copysign(std::pow(std::abs(s.a1 * u.x()), pw), u.x()));
  double eta = std::copysign(0.5 * 3.141592653589793, u.z());
  if (uxy > 1e-12) {
    // Latitude: tan^(2 - eps1) eta = a3 m u3 / |u_xy| with m the norm of the section's normal.
    const double c = std::abs(std::cos(omega)), sn = std::abs(std::sin(omega));
    const double m =
        std::hypot(std::pow(c, 2.0 - s.eps2) / s.a1, std::pow(sn, 2.0 - s.eps2) / s.a2);
    eta = std::atan(std::copysign(std::pow(s.a3 * m * std::abs(u.z()) / uxy, pe), u.z()));
  }
  return surface_point(s, eta, omega);
}

// Height of the part's lowest point above the plane n . x = offset (unit n towards the part).
double support_height(const PosedSuperquadric& x, const Eigen::Vector3d& nrm, double offset) {
  const Eigen::Vector3d down = -(x.T_world_part.linear().transpose() * nrm);
  return nrm.dot(x.T_world_part * extreme_point(x.shape, down)) - offset;
}

struct Problem {
  std::span<const Eigen::Vector3d> points;
  std::vector<std::uint32_t> all;  // 0..n-1 for SuperquadricMetric::values
  ShapeFitOptions o;
  int model_params() const { return o.fit_taper ? kModel : kModel - 2; }

  Lin linearise(const PosedSuperquadric& x) const {
    const std::size_t n = points.size();
    const SuperquadricMetric m(x.shape);
    const double w = volume_factor(x.shape, o);
    const Eigen::Isometry3d T_part_world = x.T_world_part.inverse();
    const Eigen::Matrix3d R = x.T_world_part.linear();
    // Model columns by forward differences: G at every point for each nudged parameter (the
    // vectorised metric), stepping away from a bound the parameter sits on.
    std::array<std::vector<double>, kModel> g_nudged;
    std::array<double, kModel> step{}, w_nudged{};
    for (int j = 0; j < model_params(); ++j) {
      const double v = get(x.shape, j);
      double h = j < 3 ? 1e-5 : 1e-5 * std::max(1.0, std::abs(v));
      const bool at_top = (j == 3 || j == 4) ? v + h > o.max_eps : (j >= 5 && v + h > o.max_taper);
      if (at_top) h = -h;
      const Superquadric s = set(x.shape, j, v + h, o);
      step[j] = get(s, j) - v;
      w_nudged[j] = volume_factor(s, o);
      g_nudged[j].resize(n);
      SuperquadricMetric(s).values(T_part_world, points, all, g_nudged[j]);
    }
    Lin lin;
    Eigen::Matrix<double, kN, 1> jrow;
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d q = T_part_world * points[i];
      Eigen::Vector3d grad;
      const double g = m.value_and_gradient(q, grad);
      const double qn = q.norm();
      const PointResidual p = point_residual(g, grad, q, o.residual);
      const double r = w * p.r;
      jrow.head<3>() = -w * (R * p.dr_dq);
      jrow.segment<3>(3) = w * p.dr_dq.cross(q);
      jrow.tail<kModel>().setZero();
      for (int j = 0; j < model_params(); ++j) {
        jrow[6 + j] =
            step[j] != 0.0
                ? (w_nudged[j] * nudged_residual(g_nudged[j][i], qn, p.scale, o.residual) - r) /
                      step[j]
                : 0.0;
      }
      lin.cost += 0.5 * r * r;
      lin.jtj.selfadjointView<Eigen::Upper>().rankUpdate(jrow);
      lin.g += jrow * r;
    }
    lin.jtj.triangularView<Eigen::StrictlyLower>() = lin.jtj.transpose();
    add_support(x, n, lin);
    return lin;
  }

  // The part's lowest point along the table normal held on the table: one residual weighted
  // like support_weight x the points, its Jacobian by differences (a single cheap value).
  void add_support(const PosedSuperquadric& x, std::size_t n, Lin& lin) const {
    if (!o.support_plane) return;
    const double k = std::sqrt(o.support_weight * static_cast<double>(n));
    const auto height = [&](const PosedSuperquadric& p) {
      return support_height(p, o.support_plane->head<3>(), (*o.support_plane)[3]);
    };
    const double r = k * height(x);
    Eigen::Matrix<double, kN, 1> j = Eigen::Matrix<double, kN, 1>::Zero();
    j.head<3>() = k * o.support_plane->head<3>();
    constexpr double kH = 1e-6;
    for (int c = 3; c < 6 + model_params(); ++c) {
      Vector h = Vector::Zero();
      h[c] = kH;
      const PosedSuperquadric nudged = step(x, h);
      const double dv = c >= 6 ? get(nudged.shape, c - 6) - get(x.shape, c - 6) : kH;
      j[c] = dv != 0.0 ? k * (height(nudged) - height(x)) / dv : 0.0;
    }
    lin.cost += 0.5 * r * r;
    lin.jtj.noalias() += j * j.transpose();
    lin.g.noalias() += j * r;
  }

  PosedSuperquadric step(const PosedSuperquadric& x, const Vector& h) const {
    PosedSuperquadric out = x;
    out.T_world_part.translation() += h.head<3>();
    const Eigen::Vector3d w = h.segment<3>(3);
    const double angle = w.norm();
    if (angle > 0.0) {
      out.T_world_part.linear() =
          x.T_world_part.linear() * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
    }
    for (int j = 0; j < model_params(); ++j) {
      out.shape = set(out.shape, j, get(x.shape, j) + h[6 + j], o);
    }
    return out;
  }
};

}  // namespace

double support_height(const PosedSuperquadric& part, const Eigen::Vector4d& plane) {
  return support_height(part, plane.head<3>(), plane[3]);
}

ShapeFitResult fit_superquadric(std::span<const Eigen::Vector3d> points,
                                const PosedSuperquadric& initial, const ShapeFitOptions& options) {
  ShapeFitResult result;
  result.part = initial;
  const bool finite = std::all_of(points.begin(), points.end(),
                                  [](const Eigen::Vector3d& p) { return p.allFinite(); });
  if (points.size() < kN || !finite || !initial.shape.valid() ||
      !initial.T_world_part.matrix().allFinite() || !(options.reference_volume > 0.0)) {
    return result;
  }
  Problem problem{points, std::vector<std::uint32_t>(points.size()), options};
  std::iota(problem.all.begin(), problem.all.end(), 0u);
  PosedSuperquadric start = initial;
  start.shape = clamp(start.shape, options);
  LmOptions lm;
  lm.max_iterations = options.max_iterations;
  lm.gradient_tolerance = 1e-12;
  lm.step_tolerance = options.step_tolerance;
  const auto out = levenberg_marquardt<kN>(
      start, lm, [&](const PosedSuperquadric& x) { return problem.linearise(x); },
      [&](const PosedSuperquadric& x, const Vector& h) { return problem.step(x, h); },
      [](const PosedSuperquadric& x) { return x.T_world_part.translation().norm(); });
  result.part = out.x;
  result.cost = out.lin.cost;
  result.iterations = out.iterations;
  const SuperquadricMetric m(out.x.shape);
  const Eigen::Isometry3d inv = out.x.T_world_part.inverse();
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const double r = m.value(inv * p) - 1.0;
    sum += r * r;
  }
  result.measure = std::sqrt(sum / static_cast<double>(points.size()));
  result.ok = true;
  return result;
}

}  // namespace rangefit
