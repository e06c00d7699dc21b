#include "detect/bore/cylinder_lsf.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "detect/common/lanes.hpp"
#include "detect/common/pca.hpp"

namespace rangefit {
namespace {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

double huber(double r, double delta) {
  const double a = std::abs(r);
  return delta <= 0.0 || a <= delta ? 0.5 * r * r : delta * (a - 0.5 * delta);
}

// Distance of q from the axis line (unit axis) without a cross product: the inner loop of
// every cost evaluation. |d|^2 - h^2 loses ~1e-14 mm at 100 mm from the axis point.
inline double radial(const Eigen::Vector3d& q, const Cylinder& c) {
  const Eigen::Vector3d d = q - c.point;
  const double h = d.dot(c.axis);
  return std::sqrt(std::max(d.squaredNorm() - h * h, 0.0));
}

double cost(std::span<const Eigen::Vector3d> pts, const Cylinder& c, double delta) {
  double s = 0.0;
  for (const auto& q : pts) s += huber(radial(q, c) - c.radius, delta);
  return s;
}

// Parameters: axis point moved by (x, y) along b1, b2; axis tilted by (wx, wy) toward b1, b2;
// radius changed by dr. Both b1 and b2 are normal to the current axis.
Cylinder apply(const Cylinder& c, const Vector5d& d) {
  const Eigen::Vector3d b1 = c.axis.unitOrthogonal(), b2 = c.axis.cross(b1);
  Cylinder n = c;
  n.point = c.point + d(0) * b1 + d(1) * b2;
  n.axis = (c.axis + d(2) * b1 + d(3) * b2).normalized();
  n.radius = c.radius + d(4);
  return n;
}

// One point's residual r = |w| - radius, its analytic Jacobian row j and the IRLS weight of the
// Huber loss; false for a point on the axis (no direction, no gradient).
struct PointTerm {
  Vector5d j;
  double r = 0.0;
  double weight = 1.0;
};

bool point_term(const Eigen::Vector3d& q, const Cylinder& c, const Eigen::Vector3d& b1,
                const Eigen::Vector3d& b2, double delta, double trim, PointTerm& t) {
  const Eigen::Vector3d d = q - c.point;
  const double h = d.dot(c.axis);
  const Eigen::Vector3d w = d - h * c.axis;
  const double dist = w.norm();
  if (dist < 1e-12) return false;
  const double mb1 = w.dot(b1) / dist, mb2 = w.dot(b2) / dist;
  t.r = dist - c.radius;
  t.j << -mb1, -mb2, -h * mb1, -h * mb2, -1.0;
  t.weight = delta <= 0.0 || std::abs(t.r) <= delta ? 1.0 : delta / std::abs(t.r);
  return !(trim > 0.0 && std::abs(t.r) > trim);
}

// Gauss-Newton system J^T W J and gradient J^T W r: the hot loop of the refinement. Each point
// in the axis frame (x, y along b1, b2; h along the axis), the 15 distinct entries of the
// symmetric J^T W J as scalars (no 5x5 outer product per point), four points per step in the
// lanes of a V4d (lanes.hpp: compiled for SSE2 and AVX2); a point on the axis (no direction, no
// gradient) or beyond the trim gets no weight. s: the 14 sums of J^T W J named below, the 5 of
// J^T W r, then the weighted sum of squared residuals.
struct Frame {
  double px, py, pz, b1x, b1y, b1z, b2x, b2y, b2z, ax, ay, az;
};

template <class V>
[[gnu::always_inline]] inline void equations_lanes(const Eigen::Vector3d* pts, std::size_t n,
                                                   const Frame& f, double radius, double delta,
                                                   double trim, double* s) {
  V a11{}, a12{}, a13{}, a14{}, a15{}, a22{}, a24{}, a25{}, a33{}, a34{}, a35{}, a44{}, a45{},
      a55{}, g1{}, g2{}, g3{}, g4{}, g5{}, rr{};
  const V one = lanes::splat<V>(1.0), zero = lanes::splat<V>(0.0);
  for (std::size_t k = 0; k < n; k += 4) {
    V qx, qy, qz;
    for (std::size_t l = 0; l < 4; ++l) {
      // Past the end: the axis point itself, which gets no weight.
      const bool in = k + l < n;
      qx[l] = in ? pts[k + l].x() : f.px;
      qy[l] = in ? pts[k + l].y() : f.py;
      qz[l] = in ? pts[k + l].z() : f.pz;
    }
    const V dx = qx - f.px, dy = qy - f.py, dz = qz - f.pz;
    const V x = dx * f.b1x + dy * f.b1y + dz * f.b1z;
    const V y = dx * f.b2x + dy * f.b2y + dz * f.b2z;
    const V h = dx * f.ax + dy * f.ay + dz * f.az;
    const V dist2 = x * x + y * y;
    const auto on_axis = dist2 < 1e-24;
    const V dist = lanes::sqrt(on_axis ? one : dist2);
    const V r = dist - radius, ar = lanes::abs(r);
    V w = delta <= 0.0 ? one : (ar <= delta ? one : delta / ar);
    w = on_axis ? zero : w;
    if (trim > 0.0) w = ar > trim ? zero : w;
    // J = (-m1, -m2, -h m1, -h m2, -1) with m = (x, y) / dist.
    const V inv = one / dist;
    const V m1 = x * inv, m2 = y * inv;
    const V wm1 = w * m1, wm2 = w * m2, hh = h * h;
    a11 += wm1 * m1;
    a12 += wm1 * m2;
    a22 += wm2 * m2;
    a13 += wm1 * m1 * h;
    a14 += wm1 * m2 * h;
    a24 += wm2 * m2 * h;
    a33 += wm1 * m1 * hh;
    a34 += wm1 * m2 * hh;
    a44 += wm2 * m2 * hh;
    a15 += wm1;
    a25 += wm2;
    a35 += wm1 * h;
    a45 += wm2 * h;
    a55 += w;
    const V wr = w * r;
    g1 += wr * m1;
    g2 += wr * m2;
    g3 += wr * m1 * h;
    g4 += wr * m2 * h;
    g5 += wr;
    rr += wr * r;
  }
  const V* sums[] = {&a11, &a12, &a13, &a14, &a15, &a22, &a24, &a25, &a33, &a34,
                     &a35, &a44, &a45, &a55, &g1,  &g2,  &g3,  &g4,  &g5,  &rr};
  for (std::size_t i = 0; i < 20; ++i) {
    const V& v = *sums[i];
    s[i] = (v[0] + v[1]) + (v[2] + v[3]);
  }
}

void equations_sse2(const Eigen::Vector3d* pts, std::size_t n, const Frame& f, double radius,
                    double delta, double trim, double* s) {
  equations_lanes<lanes::V4d>(pts, n, f, radius, delta, trim, s);
}
#ifdef RANGEFIT_LANES_AVX2
[[gnu::target("avx2")]] void equations_avx2(const Eigen::Vector3d* pts, std::size_t n,
                                            const Frame& f, double radius, double delta,
                                            double trim, double* s) {
  equations_lanes<lanes::V4d>(pts, n, f, radius, delta, trim, s);
}
#endif

// Returns the weighted sum of squared residuals.
double normal_equations(std::span<const Eigen::Vector3d> pts, const Cylinder& c, double delta,
                        double trim, Matrix5d& jtj, Vector5d& jtr) {
  const Eigen::Vector3d b1 = c.axis.unitOrthogonal(), b2 = c.axis.cross(b1);
  const Frame f{c.point.x(), c.point.y(), c.point.z(), b1.x(),     b1.y(),     b1.z(),
                b2.x(),      b2.y(),      b2.z(),      c.axis.x(), c.axis.y(), c.axis.z()};
  double s[20];
#ifdef RANGEFIT_LANES_AVX2
  if (lanes::cpu_has_avx2()) {
    equations_avx2(pts.data(), pts.size(), f, c.radius, delta, trim, s);
  } else {
    equations_sse2(pts.data(), pts.size(), f, c.radius, delta, trim, s);
  }
#else
  equations_sse2(pts.data(), pts.size(), f, c.radius, delta, trim, s);
#endif
  const double a11 = s[0], a12 = s[1], a13 = s[2], a14 = s[3], a15 = s[4], a22 = s[5];
  const double a24 = s[6], a25 = s[7], a33 = s[8], a34 = s[9], a35 = s[10], a44 = s[11];
  const double a45 = s[12], a55 = s[13];
  const double a23 = a14;          // (m2)(m1 h)
  jtj << a11, a12, a13, a14, a15,  //
      a12, a22, a23, a24, a25,     //
      a13, a23, a33, a34, a35,     //
      a14, a24, a34, a44, a45,     //
      a15, a25, a35, a45, a55;
  jtr << -s[14], -s[15], -s[16], -s[17], -s[18];
  return s[19];
}

// Gradient J^T W r alone: all a steepest-descent step needs (no 5x5 outer products).
Vector5d gradient(std::span<const Eigen::Vector3d> pts, const Cylinder& c, double delta) {
  const Eigen::Vector3d b1 = c.axis.unitOrthogonal(), b2 = c.axis.cross(b1);
  Vector5d g = Vector5d::Zero();
  PointTerm t;
  for (const auto& q : pts) {
    if (point_term(q, c, b1, b2, delta, 0.0, t)) g.noalias() += t.weight * t.r * t.j;
  }
  return g;
}

// Keeps the axis point at the foot of the points' centroid, so the tilt parameters act about
// the data and stay well conditioned.
Cylinder recentre(const Eigen::Vector3d& m, Cylinder c) {
  c.point += (m - c.point).dot(c.axis) * c.axis;
  return c;
}

}  // namespace

namespace {

// The state of a fit between iterations.
struct Search {
  Cylinder c;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double half_length = 0.0;  // of the data along the axis, for the step tolerance
  double f = -1.0;           // cost at c; < 0: not evaluated yet
  double lambda = 1e-3;      // Levenberg-Marquardt damping
  double step = 1e-4;        // steepest descent step length, adapted
};

// The centroid (the axis point is kept at its foot) and, for the step tolerance, the data's
// half-length along the axis in the same pass (sqrt(3) sigma: that of evenly spread points).
void data_extent(std::span<const Eigen::Vector3d> pts, const CylinderLsfOptions& o, Search& s) {
  if (!(o.step_tolerance > 0.0)) {
    s.centroid = pca::centroid(pts);
    return;
  }
  double sh = 0.0, shh = 0.0;
  for (const auto& q : pts) {
    s.centroid += q;
    const double h = (q - s.c.point).dot(s.c.axis);
    sh += h;
    shh += h * h;
  }
  const double n = static_cast<double>(pts.size());
  s.centroid /= n;
  s.half_length = std::sqrt(3.0 * std::max(shh / n - (sh / n) * (sh / n), 0.0));
}

Vector5d damped_step(const Matrix5d& jtj, const Vector5d& jtr, double lambda) {
  Matrix5d a = jtj;
  a.diagonal() += lambda * (jtj.diagonal().array() + 1e-9).matrix();
  return -a.ldlt().solve(jtr);
}

// How far a step moves the surface: axis shift, tilt times the half-length, radius change.
double surface_move(const Vector5d& d, double half_length) {
  return std::max({d.head<2>().norm(), d.segment<2>(2).norm() * half_length, std::abs(d(4))});
}

enum class Outcome { kImproved, kConverged, kStuck };

// One Levenberg-Marquardt iteration's damping search: a cheaper cost or, with the step
// tolerance, a first step too small to matter (at the minimum: no cost to evaluate).
Outcome lm_search(std::span<const Eigen::Vector3d> pts, const CylinderLsfOptions& o,
                  const Matrix5d& jtj, const Vector5d& jtr, Search& s, Cylinder& next,
                  double& f_new) {
  for (int tries = 0; tries < 10; ++tries) {
    const Vector5d d = damped_step(jtj, jtr, s.lambda);
    next = recentre(s.centroid, apply(s.c, d));
    if (o.step_tolerance > 0.0 && tries == 0 && surface_move(d, s.half_length) < o.step_tolerance) {
      s.c = next;
      return Outcome::kConverged;
    }
    if (s.f < 0.0) s.f = cost(pts, s.c, o.huber_delta);
    f_new = cost(pts, next, o.huber_delta);
    const bool improved = f_new < s.f;
    s.lambda = improved ? std::max(s.lambda / 3.0, 1e-12) : s.lambda * 4.0;
    if (improved) return Outcome::kImproved;
  }
  return Outcome::kStuck;
}

// Steepest descent with a backtracking step, as the thesis's baseline (4.2.4).
Outcome sd_search(std::span<const Eigen::Vector3d> pts, const CylinderLsfOptions& o,
                  const Vector5d& jtr, Search& s, Cylinder& next, double& f_new) {
  if (s.f < 0.0) s.f = cost(pts, s.c, o.huber_delta);
  for (int tries = 0; tries < 20; ++tries) {
    next = recentre(s.centroid, apply(s.c, -s.step * jtr));
    f_new = cost(pts, next, o.huber_delta);
    const bool improved = f_new < s.f;
    s.step = improved ? s.step * 1.5 : s.step * 0.5;
    if (improved) return Outcome::kImproved;
  }
  return Outcome::kStuck;
}

// Takes the improved step; true when it ends the fit (relative decrease or surface move below
// the tolerances).
bool accept(const Cylinder& next, double f_new, const CylinderLsfOptions& o, Search& s) {
  const double decrease = (s.f - f_new) / std::max(s.f, 1e-300);
  const Eigen::Vector3d shift = next.point - s.c.point;
  const double moved =
      std::max({(shift - shift.dot(s.c.axis) * s.c.axis).norm(),
                (next.axis - s.c.axis).norm() * s.half_length, std::abs(next.radius - s.c.radius)});
  s.c = next;
  s.f = f_new;
  return decrease < o.tolerance || moved < o.step_tolerance;
}

}  // namespace

CylinderLsfResult fit_cylinder_lsf(std::span<const Eigen::Vector3d> pts, const Cylinder& initial,
                                   const CylinderLsfOptions& o) {
  CylinderLsfResult res;
  res.cylinder = initial;
  if (pts.size() < 5 || !(initial.radius > 0.0) || !(initial.axis.norm() > 0.0)) return res;
  Search s;
  s.c = initial;
  s.c.axis.normalize();
  data_extent(pts, o, s);
  s.c = recentre(s.centroid, s.c);
  // The starting cost only once a step has to be judged: a fit that starts at its minimum
  // (the polish of a converged fit) ends on the first step, under the step tolerance.
  if (!(o.step_tolerance > 0.0)) s.f = cost(pts, s.c, o.huber_delta);
  // The unchecked step is a Gauss-Newton step: damping would shorten it along the poorly
  // determined directions (a narrow arc's radius and offset), which it has to cross in one go.
  if (o.single_unchecked_step) s.lambda = 1e-12;
  const bool lm = o.method == LsfMethod::kLevenbergMarquardt;
  Matrix5d jtj;
  Vector5d jtr;
  for (res.iterations = 0; res.iterations < o.max_iterations; ++res.iterations) {
    if (lm) {
      normal_equations(pts, s.c, o.huber_delta, o.trim, jtj, jtr);
    } else {
      jtr = gradient(pts, s.c, o.huber_delta);
    }
    if (o.single_unchecked_step && lm) {
      const Vector5d d = damped_step(jtj, jtr, s.lambda);
      s.c = recentre(s.centroid, apply(s.c, d));
      const bool small = surface_move(d, s.half_length) < o.step_tolerance;
      if (small || res.iterations + 1 >= o.max_iterations) {
        res.cylinder = s.c;
        res.converged = small || o.max_iterations == 1;
        res.iterations += 1;
        return res;  // no rms: the polish's caller does not need it
      }
      continue;
    }
    Cylinder next = s.c;
    double f_new = s.f;
    const Outcome out =
        lm ? lm_search(pts, o, jtj, jtr, s, next, f_new) : sd_search(pts, o, jtr, s, next, f_new);
    // No descent step left: at a minimum within precision.
    res.converged = out != Outcome::kImproved || accept(next, f_new, o, s);
    if (res.converged) {
      if (out != Outcome::kStuck) ++res.iterations;
      break;
    }
  }
  double ss = 0.0;
  for (const auto& q : pts) ss += std::pow(radial(q, s.c) - s.c.radius, 2);
  res.rms = std::sqrt(ss / static_cast<double>(pts.size()));
  res.cylinder = s.c;
  return res;
}

CylinderSigma cylinder_sigma(std::span<const Eigen::Vector3d> pts, const Cylinder& c, double trim) {
  CylinderSigma out;
  if (pts.size() < 6 || !(c.radius > 0.0) || !(c.axis.norm() > 0.0)) return out;
  Cylinder at = c;
  at.axis.normalize();
  at = recentre(pca::centroid(pts), at);  // tilt about the data: offset and tilt uncorrelated
  Matrix5d jtj;
  Vector5d jtr;
  const double ss = normal_equations(pts, at, 0.0, trim, jtj, jtr);
  const double n = jtj(4, 4);  // plain least squares: the count of points within the trim
  if (!(n > 6.0)) return out;
  const Eigen::LDLT<Matrix5d> ldlt(jtj);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return out;
  const Matrix5d cov = (ss / (n - 5.0)) * ldlt.solve(Matrix5d::Identity());
  if (!cov.allFinite() || !(cov.diagonal().minCoeff() > 0.0)) return out;
  out.offset = std::sqrt(cov(0, 0) + cov(1, 1));
  out.axis = std::sqrt(cov(2, 2) + cov(3, 3));
  out.radius = std::sqrt(cov(4, 4));
  out.rms = std::sqrt(ss / n);
  out.points = static_cast<std::size_t>(n);
  out.valid = true;
  return out;
}

Cylinder cylinder_from_pca(std::span<const Eigen::Vector3d> pts, double radius) {
  const pca::Line line = pca::fit_line(pts);
  return {line.point, line.direction, radius};
}

}  // namespace rangefit
