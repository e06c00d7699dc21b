#include "detect/object/superquadric.hpp"

#include <algorithm>
#include <cmath>

#include "detect/object/superquadric_eval.hpp"

namespace rangefit {
namespace {

// Signed power used by the explicit form (eq. 2.14).
double spow(double c, double e) { return std::copysign(std::pow(std::abs(c), e), c); }

using lanes::V4d;

// SuperquadricMetric::values, four points at a time; the tail repeats the last point.
[[gnu::always_inline]] inline void values_lanes(const SuperquadricMetric& m,
                                                const Eigen::Isometry3d& T,
                                                std::span<const Eigen::Vector3d> points,
                                                std::span<const std::uint32_t> indices,
                                                std::span<double> out) {
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d t = T.translation();
  const std::size_t n = indices.size();
  for (std::size_t k = 0; k < n; k += 4) {
    V4d x, y, z;
    for (std::size_t l = 0; l < 4; ++l) {
      const Eigen::Vector3d& p = points[indices[std::min(k + l, n - 1)]];
      x[l] = p.x();
      y[l] = p.y();
      z[l] = p.z();
    }
    const V4d qx = R(0, 0) * x + R(0, 1) * y + R(0, 2) * z + t.x();
    const V4d qy = R(1, 0) * x + R(1, 1) * y + R(1, 2) * z + t.y();
    const V4d qz = R(2, 0) * x + R(2, 1) * y + R(2, 2) * z + t.z();
    const V4d g = m.evaluate<V4d, false>(qx, qy, qz, nullptr, nullptr, nullptr);
    for (std::size_t l = 0; l < 4 && k + l < n; ++l) out[k + l] = g[l];
  }
}

void values_sse2(const SuperquadricMetric& m, const Eigen::Isometry3d& T,
                 std::span<const Eigen::Vector3d> points, std::span<const std::uint32_t> indices,
                 std::span<double> out) {
  values_lanes(m, T, points, indices, out);
}
#ifdef RANGEFIT_LANES_AVX2
[[gnu::target("avx2")]] void values_avx2(const SuperquadricMetric& m, const Eigen::Isometry3d& T,
                                         std::span<const Eigen::Vector3d> points,
                                         std::span<const std::uint32_t> indices,
                                         std::span<double> out) {
  values_lanes(m, T, points, indices, out);
}
#endif

}  // namespace

double Superquadric::min_size() const { return std::min({a1, a2, a3}); }
double Superquadric::max_size() const { return std::max({a1, a2, a3}); }

Superquadric ellipsoid_of(const Superquadric& sq) {
  Superquadric out = sq;
  out.eps1 = out.eps2 = 1.0;
  return out;
}

bool Superquadric::ball() const {
  return a1 == a3 && a2 == a3 && eps1 == 1.0 && eps2 == 1.0 && kx == 0.0 && ky == 0.0;
}

double support(const Superquadric& sq, const Eigen::Vector3d& m) {
  const double q_xy = 2.0 / (2.0 - sq.eps2), q_z = 2.0 / (2.0 - sq.eps1);
  const double across =
      std::pow(std::pow(std::abs(sq.a1 * m.x()), q_xy) + std::pow(std::abs(sq.a2 * m.y()), q_xy),
               1.0 / q_xy);
  return std::pow(std::pow(across, q_z) + std::pow(std::abs(sq.a3 * m.z()), q_z), 1.0 / q_z);
}

double tapered_support(const Superquadric& sq, const Eigen::Vector3d& m) {
  if (!sq.has_taper()) return support(sq, m);
  constexpr int kNodes = 48, kGoldenSteps = 24;
  const double q = 2.0 / (2.0 - sq.eps2), p_z = 2.0 / sq.eps1;
  const double ax = std::abs(sq.a1 * m.x()), ay = std::abs(sq.a2 * m.y());
  const auto at = [&](double t) {
    const double c = std::pow(std::max(0.0, 1.0 - std::pow(std::abs(t), p_z)), 0.5 * sq.eps1);
    const double x = ax * c * std::abs(1.0 + sq.kx * t), y = ay * c * std::abs(1.0 + sq.ky * t);
    const double across = sq.eps2 >= 2.0 ? std::max(x, y)  // a diamond's
                          : q == 2.0     ? std::hypot(x, y)
                                         : std::pow(std::pow(x, q) + std::pow(y, q), 1.0 / q);
    return across + m.z() * sq.a3 * t;
  };
  int best = 0;
  double best_value = -INFINITY;
  for (int i = 0; i <= kNodes; ++i) {
    const double v = at(-1.0 + 2.0 * i / kNodes);
    if (v > best_value) best_value = v, best = i;
  }
  double lo = -1.0 + 2.0 * std::max(best - 1, 0) / kNodes;
  double hi = -1.0 + 2.0 * std::min(best + 1, kNodes) / kNodes;
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
  double f1 = at(x1), f2 = at(x2);
  for (int i = 0; i < kGoldenSteps; ++i) {
    if (f1 < f2) {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = at(x2);
    } else {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = at(x1);
    }
  }
  return std::max({best_value, f1, f2});
}

bool Superquadric::valid() const {
  const auto finite_pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto in = [](double v, double lo, double hi) {
    return std::isfinite(v) && v >= lo && v <= hi;
  };
  return finite_pos(a1) && finite_pos(a2) && finite_pos(a3) && in(eps1, 0.1, 2.0) &&
         in(eps2, 0.1, 2.0) && in(kx, -1.0, 1.0) && in(ky, -1.0, 1.0);
}

SuperquadricMetric::SuperquadricMetric(const Superquadric& sq) : sq_(sq) {
  const auto make = [](double e) {
    Power p;
    p.e = e;
    const double r = std::round(e);
    if (std::abs(e - r) < 1e-9 && r >= 0.0 && r <= 64.0) p.n = static_cast<int>(r);
    return p;
  };
  p_xy_ = make(2.0 / sq.eps2);
  p_a_ = make(sq.eps2 / sq.eps1);
  p_z_ = make(2.0 / sq.eps1);
  p_g_ = make(sq.eps1);
  inv_a1_ = 1.0 / sq.a1;
  inv_a2_ = 1.0 / sq.a2;
  inv_a3_ = 1.0 / sq.a3;
  tapered_ = sq.kx != 0.0 || sq.ky != 0.0;
}

double SuperquadricMetric::value(const Eigen::Vector3d& p) const {
  return evaluate<double, false>(p.x(), p.y(), p.z(), nullptr, nullptr, nullptr);
}

double SuperquadricMetric::value_and_gradient(const Eigen::Vector3d& p,
                                              Eigen::Vector3d& gradient) const {
  return evaluate<double, true>(p.x(), p.y(), p.z(), &gradient.x(), &gradient.y(), &gradient.z());
}

void SuperquadricMetric::values(const Eigen::Isometry3d& T_part_from,
                                std::span<const Eigen::Vector3d> points,
                                std::span<const std::uint32_t> indices,
                                std::span<double> out) const {
  if (indices.empty()) return;
#ifdef RANGEFIT_LANES_AVX2
  if (lanes::cpu_has_avx2()) return values_avx2(*this, T_part_from, points, indices, out);
#endif
  values_sse2(*this, T_part_from, points, indices, out);
}

double metric(const Superquadric& sq, const Eigen::Vector3d& p_part) {
  return SuperquadricMetric(sq).value(p_part);
}

double metric_and_gradient(const Superquadric& sq, const Eigen::Vector3d& p_part,
                           Eigen::Vector3d& gradient) {
  return SuperquadricMetric(sq).value_and_gradient(p_part, gradient);
}

double inside_outside(const Superquadric& sq, const Eigen::Vector3d& p_part) {
  const double g = metric(sq, p_part);
  // F = G^(1/eps1), computed through the log so it saturates instead of overflowing.
  return std::exp(std::min(std::log(g) / sq.eps1, 690.0));
}

Eigen::Vector3d surface_point(const Superquadric& sq, double eta, double omega) {
  const double ce = spow(std::cos(eta), sq.eps1);
  const double x = sq.a1 * ce * spow(std::cos(omega), sq.eps2);
  const double y = sq.a2 * ce * spow(std::sin(omega), sq.eps2);
  const double z = sq.a3 * spow(std::sin(eta), sq.eps1);
  const double fx = 1.0 + sq.kx / sq.a3 * z;
  const double fy = 1.0 + sq.ky / sq.a3 * z;
  return {fx * x, fy * y, z};
}

Eigen::AlignedBox3d part_bounds(const Superquadric& sq) {
  const double bx = sq.a1 * (1.0 + std::abs(sq.kx));
  const double by = sq.a2 * (1.0 + std::abs(sq.ky));
  return Eigen::AlignedBox3d(Eigen::Vector3d(-bx, -by, -sq.a3), Eigen::Vector3d(bx, by, sq.a3));
}

double surface_distance(const SuperquadricMetric& m, const Eigen::Vector3d& p_part) {
  Eigen::Vector3d grad;
  const double g = m.value_and_gradient(p_part, grad);
  const double norm = grad.norm();
  return norm > 0.0 ? (g - 1.0) / norm : p_part.norm();
}

}  // namespace rangefit
