#include "detect/superquadric.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rangefit {
namespace {

// Normalised coordinates below this are treated as this (keeps logs and 1/x finite on the axis
// and at the centre; the value error is far below any measurement).
constexpr double kTinyNorm = 1e-12;
// Largest exponent passed to exp(): results stay below ~1e299, so products cannot overflow.
constexpr double kMaxLog = 690.0;
// Tapering factors are clamped here: beyond the tip of a cone the part does not exist.
constexpr double kMinTaperFactor = 1e-9;

double log_sum_exp(double a, double b) {
  const double m = std::max(a, b);
  return m + std::log1p(std::exp(-std::abs(a - b)));
}

double safe_exp(double x) { return std::exp(std::min(x, kMaxLog)); }

double sign_of(double v) { return v < 0.0 ? -1.0 : 1.0; }

// Signed power used by the explicit form (eq. 2.14).
double spow(double c, double e) { return sign_of(c) * std::pow(std::abs(c), e); }

struct Untapered {
  double x, y, z;
  double fx, fy;
  bool fx_clamped, fy_clamped;
};

// Undoes eq. 2.19-2.21: X = fx(z) x, Y = fy(z) y, Z = z.
Untapered untaper(const Superquadric& sq, const Eigen::Vector3d& p) {
  Untapered u{};
  const double fx = 1.0 + sq.kx / sq.a3 * p.z();
  const double fy = 1.0 + sq.ky / sq.a3 * p.z();
  u.fx_clamped = fx < kMinTaperFactor;
  u.fy_clamped = fy < kMinTaperFactor;
  u.fx = std::max(fx, kMinTaperFactor);
  u.fy = std::max(fy, kMinTaperFactor);
  u.x = p.x() / u.fx;
  u.y = p.y() / u.fy;
  u.z = p.z();
  return u;
}

// Log-domain pieces of eq. 2.15: lx = (2/e2) ln|x/a1|, u = (e2/e1) ln A, v = (2/e1) ln|z/a3|.
struct LogTerms {
  double lx, ly, log_a, u, v, log_f;
  double nx, ny, nz;  // clamped normalised magnitudes
};

LogTerms log_terms(const Superquadric& sq, double x, double y, double z) {
  LogTerms t{};
  t.nx = std::max(std::abs(x) / sq.a1, kTinyNorm);
  t.ny = std::max(std::abs(y) / sq.a2, kTinyNorm);
  t.nz = std::max(std::abs(z) / sq.a3, kTinyNorm);
  t.lx = 2.0 / sq.eps2 * std::log(t.nx);
  t.ly = 2.0 / sq.eps2 * std::log(t.ny);
  t.log_a = log_sum_exp(t.lx, t.ly);
  t.u = sq.eps2 / sq.eps1 * t.log_a;
  t.v = 2.0 / sq.eps1 * std::log(t.nz);
  t.log_f = log_sum_exp(t.u, t.v);
  return t;
}

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

double inside_outside(const Superquadric& sq, const Eigen::Vector3d& p_part) {
  const Untapered u = untaper(sq, p_part);
  const LogTerms t = log_terms(sq, u.x, u.y, u.z);
  return std::exp(std::min(t.log_f, 690.0));
}

double metric(const Superquadric& sq, const Eigen::Vector3d& p_part) {
  const Untapered u = untaper(sq, p_part);
  const LogTerms t = log_terms(sq, u.x, u.y, u.z);
  return safe_exp(sq.eps1 * t.log_f);
}

double metric_and_gradient(const Superquadric& sq, const Eigen::Vector3d& p_part,
                           Eigen::Vector3d& gradient) {
  const Untapered u = untaper(sq, p_part);
  const LogTerms t = log_terms(sq, u.x, u.y, u.z);
  const double log_g = sq.eps1 * t.log_f;
  // dG/dx = 2 G w_u w_x / x with w_u = e^(u - lnF), w_x = e^(lx - lnA); dG/dz = 2 G w_v / z.
  // Summed in the log domain so that huge G and tiny weights never meet as separate numbers.
  const double log2 = std::log(2.0);
  const double gx = sign_of(u.x) * safe_exp(log_g + log2 + (t.u - t.log_f) + (t.lx - t.log_a) -
                                            std::log(t.nx * sq.a1));
  const double gy = sign_of(u.y) * safe_exp(log_g + log2 + (t.u - t.log_f) + (t.ly - t.log_a) -
                                            std::log(t.ny * sq.a2));
  const double gz =
      sign_of(u.z) * safe_exp(log_g + log2 + (t.v - t.log_f) - std::log(t.nz * sq.a3));
  // Chain rule through the inverse taper: x = X / fx(Z), dx/dZ = -x kx / (a3 fx).
  const double dx_dz = u.fx_clamped ? 0.0 : -u.x * sq.kx / (sq.a3 * u.fx);
  const double dy_dz = u.fy_clamped ? 0.0 : -u.y * sq.ky / (sq.a3 * u.fy);
  gradient.x() = gx / u.fx;
  gradient.y() = gy / u.fy;
  gradient.z() = gz + gx * dx_dz + gy * dy_dz;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(gradient[i])) gradient[i] = 0.0;
  }
  return safe_exp(log_g);
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
