#include "detect/cylinder_lsf.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "detect/pca.hpp"

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

CylinderLsfResult fit_cylinder_lsf(std::span<const Eigen::Vector3d> pts, const Cylinder& initial,
                                   const CylinderLsfOptions& o) {
  CylinderLsfResult res;
  res.cylinder = initial;
  if (pts.size() < 5 || !(initial.radius > 0.0) || !(initial.axis.norm() > 0.0)) return res;
  Cylinder c = initial;
  c.axis.normalize();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double half_length = 0.0;  // of the data along the axis, for the step tolerance
  if (o.step_tolerance > 0.0) {
    // One pass: the centroid and the spread along the axis (sqrt(3) sigma: the half-length of
    // evenly spread points).
    double sh = 0.0, shh = 0.0;
    for (const auto& q : pts) {
      centroid += q;
      const double h = (q - c.point).dot(c.axis);
      sh += h;
      shh += h * h;
    }
    const double n = static_cast<double>(pts.size());
    centroid /= n;
    half_length = std::sqrt(3.0 * std::max(shh / n - (sh / n) * (sh / n), 0.0));
  } else {
    centroid = pca::centroid(pts);
  }
  c = recentre(centroid, c);
  // The starting cost only once a step has to be judged: a fit that starts at its minimum
  // (the polish of a converged fit) ends on the first step, under the step tolerance.
  double f = o.step_tolerance > 0.0 ? -1.0 : cost(pts, c, o.huber_delta);
  // The unchecked step is a Gauss-Newton step: damping would shorten it along the poorly
  // determined directions (a narrow arc's radius and offset), which it has to cross in one go.
  double lambda = o.single_unchecked_step ? 1e-12 : 1e-3;
  double step = 1e-4;  // steepest descent step length, adapted
  Matrix5d jtj;
  Vector5d jtr;
  for (res.iterations = 0; res.iterations < o.max_iterations; ++res.iterations) {
    if (o.method == LsfMethod::kLevenbergMarquardt) {
      normal_equations(pts, c, o.huber_delta, o.trim, jtj, jtr);
    } else {
      jtr = gradient(pts, c, o.huber_delta);
    }
    if (o.single_unchecked_step && o.method == LsfMethod::kLevenbergMarquardt) {
      Matrix5d a = jtj;
      a.diagonal() += lambda * (jtj.diagonal().array() + 1e-9).matrix();
      const Vector5d d = -a.ldlt().solve(jtr);
      c = recentre(centroid, apply(c, d));
      // A step below the step tolerance: at the minimum, no cost to evaluate.
      const bool small = std::max({d.head<2>().norm(), d.segment<2>(2).norm() * half_length,
                                   std::abs(d(4))}) < o.step_tolerance;
      if (small || res.iterations + 1 >= o.max_iterations) {
        res.cylinder = c;
        res.converged = small || o.max_iterations == 1;
        res.iterations += 1;
        return res;
      }
      continue;
    }
    bool improved = false;
    double f_new = f;
    Cylinder next = c;
    if (o.method == LsfMethod::kLevenbergMarquardt) {
      for (int tries = 0; tries < 10 && !improved; ++tries) {
        Matrix5d a = jtj;
        a.diagonal() += lambda * (jtj.diagonal().array() + 1e-9).matrix();
        const Vector5d d = -a.ldlt().solve(jtr);
        next = recentre(centroid, apply(c, d));
        if (o.step_tolerance > 0.0 && tries == 0 &&
            std::max({d.head<2>().norm(), d.segment<2>(2).norm() * half_length, std::abs(d(4))}) <
                o.step_tolerance) {
          c = next;
          res.converged = true;
          break;
        }
        if (f < 0.0) f = cost(pts, c, o.huber_delta);
        f_new = cost(pts, next, o.huber_delta);
        improved = f_new < f;
        lambda = improved ? std::max(lambda / 3.0, 1e-12) : lambda * 4.0;
      }
    } else {
      // Steepest descent with a backtracking step, as the thesis's baseline (4.2.4).
      if (f < 0.0) f = cost(pts, c, o.huber_delta);
      for (int tries = 0; tries < 20 && !improved; ++tries) {
        next = recentre(centroid, apply(c, -step * jtr));
        f_new = cost(pts, next, o.huber_delta);
        improved = f_new < f;
        step = improved ? step * 1.5 : step * 0.5;
      }
    }
    if (res.converged) {
      ++res.iterations;
      break;
    }
    if (!improved) {
      res.converged = true;  // no descent step left: at a minimum within precision
      break;
    }
    const double decrease = (f - f_new) / std::max(f, 1e-300);
    const Eigen::Vector3d shift = next.point - c.point;
    const double moved =
        std::max({(shift - shift.dot(c.axis) * c.axis).norm(),
                  (next.axis - c.axis).norm() * half_length, std::abs(next.radius - c.radius)});
    c = next;
    f = f_new;
    if (decrease < o.tolerance || moved < o.step_tolerance) {
      res.converged = true;
      ++res.iterations;
      break;
    }
  }
  double ss = 0.0;
  for (const auto& q : pts) ss += std::pow(radial(q, c) - c.radius, 2);
  res.rms = std::sqrt(ss / static_cast<double>(pts.size()));
  res.cylinder = c;
  return res;
}

Cylinder cylinder_from_pca(std::span<const Eigen::Vector3d> pts, double radius) {
  const pca::Line line = pca::fit_line(pts);
  return {line.point, line.direction, radius};
}

}  // namespace rangefit
