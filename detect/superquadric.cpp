#include "detect/superquadric.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit {
namespace {

// Tapering factors are clamped here: beyond the tip of a cone the part does not exist.
constexpr double kMinTaperFactor = 1e-9;
// Normalised coordinates below this (relative to the largest one) count as zero for gradients.
constexpr double kTinyRatio = 1e-12;
// G saturates here instead of overflowing (finite points farther than ~1e150 part sizes).
constexpr double kMaxScale = 1e150;

// Signed power used by the explicit form (eq. 2.14).
double spow(double c, double e) { return std::copysign(std::pow(std::abs(c), e), c); }

}  // namespace

double SuperquadricMetric::Power::integer_power(double x, int n) {
  double r = 1.0;
  while (n > 0) {
    if (n & 1) r *= x;
    x *= x;
    n >>= 1;
  }
  return r;
}

double Superquadric::min_size() const { return std::min({a1, a2, a3}); }
double Superquadric::max_size() const { return std::max({a1, a2, a3}); }

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
  return evaluate<false>(p, nullptr);
}

double SuperquadricMetric::value_and_gradient(const Eigen::Vector3d& p,
                                              Eigen::Vector3d& gradient) const {
  return evaluate<true>(p, &gradient);
}

template <bool kGradient>
double SuperquadricMetric::evaluate(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const {
  if constexpr (kGradient) gradient->setZero();
  // Undo eq. 2.19-2.21: X = fx(z) x, Y = fy(z) y, Z = z (skipped for untapered parts).
  double fx_raw = 1.0, fy_raw = 1.0, fx = 1.0, fy = 1.0, x = p.x(), y = p.y();
  const double z = p.z();
  if (tapered_) {
    fx_raw = 1.0 + sq_.kx / sq_.a3 * z;
    fy_raw = 1.0 + sq_.ky / sq_.a3 * z;
    fx = std::max(fx_raw, kMinTaperFactor);
    fy = std::max(fy_raw, kMinTaperFactor);
    x /= fx;
    y /= fy;
  }
  const double nx = std::abs(x) * inv_a1_, ny = std::abs(y) * inv_a2_, nz = std::abs(z) * inv_a3_;
  const double s = std::max(std::max(nx, ny), nz);
  if (!(s > 0.0)) return 0.0;  // the centre (or NaN input, which gives 0 rather than NaN)
  if (!(s <= kMaxScale)) return kMaxScale * kMaxScale;  // also catches infinity
  // Eq. 2.15 on the scaled point: every term is in [0, 1], F' in [1, 1 + 2^(eps2/eps1)].
  const double inv_s = 1.0 / s;
  const double sx = nx * inv_s, sy = ny * inv_s, sz = nz * inv_s;
  const double ax = p_xy_(sx), ay = p_xy_(sy);
  const double a = ax + ay;
  const double u = a > 0.0 ? p_a_(a) : 0.0;
  const double v = p_z_(sz);
  const double f = u + v;
  const double g = s * s * p_g_(f);  // eq. 5.1: G = F^eps1 = s^2 F'^eps1
  if constexpr (!kGradient) {
    return g;
  } else {
    // dG/dx = 2 G (u/F)(ax/A) / x and dG/dz = 2 G (v/F) / z (x, z unscaled; |x| = sx s a1).
    const double two_g_f = 2.0 * g / f;
    const double gu = a > 0.0 ? two_g_f * u / a : 0.0;
    const double gx = sx > kTinyRatio ? gu * ax / x : 0.0;
    const double gy = sy > kTinyRatio ? gu * ay / y : 0.0;
    const double gz = sz > kTinyRatio ? two_g_f * v / z : 0.0;
    Eigen::Vector3d& grad = *gradient;
    if (!tapered_) {
      grad = Eigen::Vector3d(gx, gy, gz);
    } else {
      // Chain rule through the inverse taper: x = X / fx(Z), dx/dZ = -x kx / (a3 fx).
      const double dx_dz = fx_raw < kMinTaperFactor ? 0.0 : -x * sq_.kx / (sq_.a3 * fx);
      const double dy_dz = fy_raw < kMinTaperFactor ? 0.0 : -y * sq_.ky / (sq_.a3 * fy);
      grad = Eigen::Vector3d(gx / fx, gy / fy, gz + gx * dx_dz + gy * dy_dz);
    }
    if (!grad.allFinite()) grad.setZero();
    return g;
  }
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

}  // namespace rangefit
