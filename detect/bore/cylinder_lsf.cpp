#include "detect/bore/cylinder_lsf.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

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
// symmetric J^T W J as scalars (no 5x5 outer product per point).
void normal_equations(std::span<const Eigen::Vector3d> pts, const Cylinder& c, double delta,
                      double trim, Matrix5d& jtj, Vector5d& jtr) {
  const Eigen::Vector3d b1 = c.axis.unitOrthogonal(), b2 = c.axis.cross(b1);
  double a11 = 0, a12 = 0, a13 = 0, a14 = 0, a15 = 0, a22 = 0, a23 = 0, a24 = 0, a25 = 0;
  double a33 = 0, a34 = 0, a35 = 0, a44 = 0, a45 = 0, a55 = 0;
  double g1 = 0, g2 = 0, g3 = 0, g4 = 0, g5 = 0;
  for (const auto& q : pts) {
    const Eigen::Vector3d d = q - c.point;
    const double x = d.dot(b1), y = d.dot(b2), h = d.dot(c.axis);
    const double dist2 = x * x + y * y;
    if (dist2 < 1e-24) continue;  // on the axis: no direction, no gradient
    const double dist = std::sqrt(dist2);
    const double r = dist - c.radius, ar = std::abs(r);
    if (trim > 0.0 && ar > trim) continue;
    const double w = delta <= 0.0 || ar <= delta ? 1.0 : delta / ar;
    // J = (-m1, -m2, -h m1, -h m2, -1) with m = (x, y) / dist.
    const double inv = 1.0 / dist;
    const double m1 = x * inv, m2 = y * inv;
    const double wm1 = w * m1, wm2 = w * m2, hh = h * h;
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
    const double wr = w * r;
    g1 += wr * m1;
    g2 += wr * m2;
    g3 += wr * m1 * h;
    g4 += wr * m2 * h;
    g5 += wr;
  }
  a23 = a14;                       // (m2)(m1 h)
  jtj << a11, a12, a13, a14, a15,  //
      a12, a22, a23, a24, a25,     //
      a13, a23, a33, a34, a35,     //
      a14, a24, a34, a44, a45,     //
      a15, a25, a35, a45, a55;
  jtr << -g1, -g2, -g3, -g4, -g5;
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

Cylinder cylinder_from_pca(std::span<const Eigen::Vector3d> pts, double radius) {
  const pca::Line line = pca::fit_line(pts);
  return {line.point, line.direction, radius};
}

}  // namespace rangefit
