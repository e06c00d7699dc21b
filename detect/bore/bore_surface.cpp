#include "detect/bore/bore_surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "detect/common/levenberg_marquardt.hpp"

namespace rangefit {
namespace {

// Seven parameters for either model: the entrance moved in the plane (2), the axis turned about
// the two directions across it (2), then cone: radius, half-angle, cylinder radius; ellipse: the
// turn about the axis (the major direction), radius, radius2.
constexpr int kN = 7;
using Row = Eigen::Matrix<double, kN, 1>;

// The wall's frame: columns major, axis x major, axis.
Eigen::Matrix3d frame_of(const BoreSurface& s) {
  Eigen::Matrix3d r;
  r.col(0) = s.major;
  r.col(1) = s.axis.cross(s.major);
  r.col(2) = s.axis;
  return r;
}

// Residual at q (the point in the wall's frame), its gradient in q and in the shape values.
struct Local {
  double f = 0.0;
  Eigen::Vector3d dq = Eigen::Vector3d::Zero();
  Eigen::Vector3d dshape = Eigen::Vector3d::Zero();  // cone: r, alpha, r_cyl; ellipse: -, a, b
};

Local cone_local(const BoreSurface& s, const Eigen::Vector3d& q) {
  const double rho = std::max(std::hypot(q.x(), q.y()), 1e-12);
  const double ca = std::cos(s.half_angle), sa = std::sin(s.half_angle);
  // The generator line rho = R + z tan(alpha) (z < 0 inside); distance along its normal.
  Local c;
  c.f = (rho - s.radius) * ca - q.z() * sa;
  c.dq = Eigen::Vector3d(ca * q.x() / rho, ca * q.y() / rho, -sa);
  c.dshape = Eigen::Vector3d(-ca, -(rho - s.radius) * sa - q.z() * ca, 0.0);
  if (s.cylinder_radius > 0.0 && rho - s.cylinder_radius < c.f) {
    c.f = rho - s.cylinder_radius;
    c.dq = Eigen::Vector3d(q.x() / rho, q.y() / rho, 0.0);
    c.dshape = Eigen::Vector3d(0.0, 0.0, -1.0);
  }
  return c;
}

// Radial distance: q / k lies on the ellipse, k = sqrt(x^2/a^2 + y^2/b^2).
Local ellipse_local(const BoreSurface& s, const Eigen::Vector3d& q) {
  const double a = s.radius, b = s.radius2;
  const double rho = std::max(std::hypot(q.x(), q.y()), 1e-12);
  const double k = std::max(std::sqrt(q.x() * q.x() / (a * a) + q.y() * q.y() / (b * b)), 1e-12);
  Local e;
  e.f = rho - rho / k;
  const double m = rho / (k * k * k);
  e.dq = Eigen::Vector3d(q.x() / rho * (1.0 - 1.0 / k) + m * q.x() / (a * a),
                         q.y() / rho * (1.0 - 1.0 / k) + m * q.y() / (b * b), 0.0);
  e.dshape =
      Eigen::Vector3d(0.0, -m * q.x() * q.x() / (a * a * a), -m * q.y() * q.y() / (b * b * b));
  return e;
}

Local local(const BoreSurface& s, const Eigen::Vector3d& q) {
  return s.cone ? cone_local(s, q) : ellipse_local(s, q);
}

struct PlaneBasis {
  Eigen::Vector3d u1, u2;
};

// The Jacobian row of one point (see the parameter order above).
Row jacobian_row(const BoreSurface& s, const Eigen::Matrix3d& frame, const PlaneBasis& b,
                 const Eigen::Vector3d& q, const Local& l) {
  Row j;
  const Eigen::Vector3d world = frame * l.dq;
  const Eigen::Vector3d turn = l.dq.cross(q);  // d q / d w = [q]x, turn w in the wall's frame
  j << -world.dot(b.u1), -world.dot(b.u2), turn.x(), turn.y(), 0.0, l.dshape.y(), l.dshape.z();
  j(4) = s.cone ? l.dshape.x() : turn.z();
  return j;
}

BoreSurface step(const BoreSurface& s, const PlaneBasis& b, const Row& h) {
  BoreSurface n = s;
  n.entrance += h(0) * b.u1 + h(1) * b.u2;
  const Eigen::Vector3d w(h(2), h(3), s.cone ? 0.0 : h(4));
  Eigen::Matrix3d frame = frame_of(s);
  if (w.norm() > 0.0) frame = frame * Eigen::AngleAxisd(w.norm(), w.normalized());
  n.major = frame.col(0).normalized();
  n.axis = frame.col(2).normalized();
  n.major = (n.major - n.major.dot(n.axis) * n.axis).normalized();
  if (s.cone) {
    n.radius = std::max(s.radius + h(4), 1e-3);
    n.half_angle = std::clamp(s.half_angle + h(5), 1e-4, 1.4);
    if (s.cylinder_radius > 0.0) n.cylinder_radius = std::max(s.cylinder_radius + h(6), 1e-3);
  } else {
    n.radius = std::max(s.radius + h(5), 1e-3);
    n.radius2 = std::max(s.radius2 + h(6), 1e-3);
  }
  return n;
}

struct Linearised {
  LmLinearisation<kN> lin;
  std::size_t inliers = 0;
  double sum_sq = 0.0;  // unweighted, of the inliers
};

Linearised linearise(std::span<const Eigen::Vector3d> pts, const BoreSurface& s,
                     const PlaneBasis& b, const SurfaceFitOptions& o) {
  Linearised out;
  const Eigen::Matrix3d frame = frame_of(s);
  const double delta = o.huber_delta;
  for (const auto& p : pts) {
    const Eigen::Vector3d q = frame.transpose() * (p - s.entrance);
    const Local l = local(s, q);
    const double r = std::abs(l.f);
    const double w = delta > 0.0 && r > delta ? delta / r : 1.0;  // Huber, as weights
    out.lin.cost += delta > 0.0 && r > delta ? delta * (r - 0.5 * delta) : 0.5 * r * r;
    const Row j = jacobian_row(s, frame, b, q, l);
    out.lin.jtj.selfadjointView<Eigen::Lower>().rankUpdate(j, w);
    out.lin.g += w * l.f * j;
    out.sum_sq += l.f * l.f;
    ++out.inliers;
  }
  out.lin.jtj = out.lin.jtj.selfadjointView<Eigen::Lower>();
  return out;
}

// sigma^2 (J^T W J)^-1; a parameter the model does not use (a pure cone's cylinder radius) has
// an empty row and gets a unit diagonal so the rest can be inverted.
void standard_errors(const Linearised& l, const BoreSurface& s, SurfaceFitResult& out) {
  if (l.inliers <= static_cast<std::size_t>(kN)) return;
  Eigen::Matrix<double, kN, kN> a = l.lin.jtj;
  for (int i = 0; i < kN; ++i) {
    if (!(a(i, i) > 0.0)) a(i, i) = 1.0;
  }
  const double sigma2 = l.sum_sq / static_cast<double>(l.inliers - kN);
  const Eigen::Matrix<double, kN, kN> cov =
      sigma2 * a.ldlt().solve(Eigen::Matrix<double, kN, kN>::Identity());
  const auto sd = [&](int i) { return std::sqrt(std::max(cov(i, i), 0.0)); };
  out.sigma_entrance = std::sqrt(std::max(cov(0, 0) + cov(1, 1), 0.0));
  out.sigma_axis = std::sqrt(std::max(cov(2, 2) + cov(3, 3), 0.0));
  if (s.cone) {
    out.sigma_radius = sd(4);
    out.sigma_half_angle = sd(5);
    if (s.cylinder_radius > 0.0) out.sigma_cylinder_radius = sd(6);
  } else {
    out.sigma_major = sd(4);
    out.sigma_radius = sd(5);
    out.sigma_radius2 = sd(6);
  }
}

}  // namespace

double surface_residual(const BoreSurface& s, const Eigen::Vector3d& p) {
  return local(s, frame_of(s).transpose() * (p - s.entrance)).f;
}

Eigen::Vector3d surface_normal(const BoreSurface& s, const Eigen::Vector3d& p) {
  const Eigen::Matrix3d frame = frame_of(s);
  return (frame * local(s, frame.transpose() * (p - s.entrance)).dq).normalized();
}

SurfaceFitResult fit_bore_surface(std::span<const Eigen::Vector3d> points, const BoreSurface& start,
                                  const Eigen::Vector3d& plane_normal, const SurfaceFitOptions& o) {
  SurfaceFitResult out;
  out.surface = start;
  if (points.empty()) return out;
  PlaneBasis b;
  b.u1 = plane_normal.unitOrthogonal();
  b.u2 = plane_normal.normalized().cross(b.u1);
  LmOptions lo;
  lo.max_iterations = o.max_iterations;
  lo.step_tolerance = o.step_tolerance;
  const auto lm = levenberg_marquardt<kN>(
      start, lo, [&](const BoreSurface& s) { return linearise(points, s, b, o).lin; },
      [&](const BoreSurface& s, const Row& h) { return step(s, b, h); },
      [](const BoreSurface& s) { return s.radius + s.entrance.norm() * 1e-3; });
  out.surface = lm.x;
  out.iterations = lm.iterations;
  const Linearised end = linearise(points, lm.x, b, o);
  out.inliers = end.inliers;
  out.rms = end.inliers > 0 ? std::sqrt(end.sum_sq / static_cast<double>(end.inliers)) : 0.0;
  standard_errors(end, lm.x, out);
  return out;
}

}  // namespace rangefit
