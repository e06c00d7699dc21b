#include "detect/superquadric.hpp"

#include <algorithm>
#include <cmath>

#include "detect/superquadric_eval.hpp"

namespace rangefit {
namespace {

// Signed power used by the explicit form (eq. 2.14).
double spow(double c, double e) { return std::copysign(std::pow(std::abs(c), e), c); }

}  // namespace

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
  return evaluate<double, false>(p.x(), p.y(), p.z(), nullptr, nullptr, nullptr);
}

double SuperquadricMetric::value_and_gradient(const Eigen::Vector3d& p,
                                              Eigen::Vector3d& gradient) const {
  return evaluate<double, true>(p.x(), p.y(), p.z(), &gradient.x(), &gradient.y(), &gradient.z());
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
