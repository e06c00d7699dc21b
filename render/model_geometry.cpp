#include "render/model_geometry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rangefit::render {
namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

BoreSurface bore_surface(const DrawnBore& bore) {
  BoreSurface s;
  s.entrance = bore.entrance;
  s.axis = bore.axis.normalized();
  s.radius = bore.radius;
  s.cone = bore.shape && bore.shape->cone;
  if (s.cone) {
    s.half_angle = bore.shape->half_angle;
    s.cylinder_radius = bore.shape->cylinder_radius;
    s.major = s.axis.unitOrthogonal();
    return s;
  }
  // A circular cylinder is the ellipse of equal semi-axes.
  s.radius2 = bore.shape ? bore.shape->radius2 : bore.radius;
  const Eigen::Vector3d m = bore.shape ? bore.shape->major_axis : Eigen::Vector3d::Zero();
  const Eigen::Vector3d across = m - m.dot(s.axis) * s.axis;
  s.major = across.norm() > 1e-9 ? Eigen::Vector3d(across.normalized()) : s.axis.unitOrthogonal();
  return s;
}

double wall_depth(const DrawnBore& bore, double depth) {
  const BoreSurface s = bore_surface(bore);
  if (!s.cone || s.cylinder_radius > 0.0 || !(std::tan(s.half_angle) > 0.0)) return depth;
  return std::min(depth, s.radius / std::tan(s.half_angle));  // a pure cone ends in its apex
}

namespace {

// The wall's point at `t` below the entrance (along the axis) and angle w about it from the
// major direction: the ellipse (x/a)^2 + (y/b)^2 = 1, or the cone's radius at that depth, not
// below the cylinder it ends in.
Eigen::Vector3d wall_point(const BoreSurface& s, double t, double w) {
  const Eigen::Vector3d minor = s.axis.cross(s.major);
  double a = s.radius, b = s.radius2;
  if (s.cone) a = b = std::max(s.radius - t * std::tan(s.half_angle), s.cylinder_radius);
  return s.entrance - t * s.axis + a * std::cos(w) * s.major + b * std::sin(w) * minor;
}

}  // namespace

std::vector<Polyline> bore_wireframe(const DrawnBore& bore, double depth) {
  const BoreSurface s = bore_surface(bore);
  depth = wall_depth(bore, depth);
  // Rings at the entrance, half way, the bottom and where a countersink's cone meets its
  // cylinder; generators through those depths (bent there).
  std::vector<double> rings = {0.0, 0.5 * depth, depth};
  if (s.cone && s.cylinder_radius > 0.0 && std::tan(s.half_angle) > 0.0) {
    const double bend = (s.radius - s.cylinder_radius) / std::tan(s.half_angle);
    if (bend < depth) rings.push_back(bend);
  }
  std::sort(rings.begin(), rings.end());
  std::vector<Polyline> lines;
  constexpr int kRingSegments = 72;
  for (const double t : rings) {
    Polyline ring;
    for (int k = 0; k <= kRingSegments; ++k) {
      ring.points.push_back(wall_point(s, t, 2.0 * kPi * k / kRingSegments));
    }
    lines.push_back(std::move(ring));
  }
  constexpr int kGenerators = 12;
  for (int k = 0; k < kGenerators; ++k) {
    Polyline generator;
    for (const double t : rings)
      generator.points.push_back(wall_point(s, t, 2.0 * kPi * k / kGenerators));
    lines.push_back(std::move(generator));
  }
  lines.push_back({LineRole::kAxis,
                   {bore.entrance - depth * s.axis, bore.entrance + 1.5 * bore.radius * s.axis},
                   {}});
  return lines;
}

std::vector<Polyline> part_wireframe(const DrawnPart& part) {
  const Superquadric& sq = part.shape;
  const Eigen::Isometry3d& T = part.T_world_part;
  std::vector<Polyline> lines;
  constexpr int kSegments = 64;
  constexpr int kParallels = 7;  // between the poles, the equator among them
  const auto add = [&](Polyline& line, double eta, double omega) {
    const Eigen::Vector3d p = surface_point(sq, eta, omega);
    Eigen::Vector3d gradient;
    metric_and_gradient(sq, p, gradient);
    line.points.push_back(T * p);
    line.normals.push_back(T.linear() * gradient.normalized());
  };
  for (int i = 1; i <= kParallels; ++i) {
    // Evenly spaced along z (z = a3 sin^eps1 eta): for a small eps1 (a cylinder) even steps of
    // eta would crowd every parallel at the caps.
    const double f = -1.0 + 2.0 * i / (kParallels + 1);
    const double eta = std::copysign(std::asin(std::pow(std::abs(f), 1.0 / sq.eps1)), f);
    Polyline line;
    for (int k = 0; k <= kSegments; ++k) add(line, eta, -kPi + 2.0 * kPi * k / kSegments);
    lines.push_back(std::move(line));
  }
  constexpr int kMeridians = 12;
  for (int j = 0; j < kMeridians; ++j) {
    const double omega = -kPi + 2.0 * kPi * j / kMeridians;
    Polyline line;
    for (int k = 0; k <= kSegments; ++k) add(line, -0.5 * kPi + kPi * k / kSegments, omega);
    lines.push_back(std::move(line));
  }
  const Eigen::Vector3d c = T.translation();
  const double sizes[3] = {sq.a1, sq.a2, sq.a3};
  const LineRole roles[3] = {LineRole::kAxisX, LineRole::kAxisY, LineRole::kAxisZ};
  for (int i = 0; i < 3; ++i) {
    lines.push_back({roles[i], {c, c + 1.3 * sizes[i] * T.linear().col(i)}, {}});
  }
  return lines;
}

double bore_depth(const DrawnBore& bore, std::span<const Eigen::Vector3d> points) {
  if (bore.depth > 0.0) return bore.depth;
  const BoreSurface s = bore_surface(bore);
  std::vector<double> behind;
  for (const Eigen::Vector3d& p : points) {
    const double t = -(p - bore.entrance).dot(s.axis);
    if (!(t > 0.0) || t > 50.0 * bore.radius) continue;
    if (std::abs(surface_residual(s, p)) <= 0.1 * bore.radius) behind.push_back(t);
  }
  if (behind.size() < 10) return 2.0 * bore.radius;
  const auto k = static_cast<std::ptrdiff_t>(0.98 * static_cast<double>(behind.size() - 1));
  std::nth_element(behind.begin(), behind.begin() + k, behind.end());
  return std::max(behind[static_cast<std::size_t>(k)], 0.2 * bore.radius);
}

Eigen::Vector3d entrance_plane_normal(const DrawnBore& bore,
                                      std::span<const Eigen::Vector3d> points) {
  const Eigen::Vector3d a = bore.axis.normalized();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - bore.entrance;
    const double along = d.dot(a), across = (d - along * a).norm();
    if (!d.allFinite() || across < 1.1 * bore.radius || d.norm() > 2.0 * bore.radius) continue;
    sum += d;
    outer += d * d.transpose();
    ++n;
  }
  if (n < 10) return a;
  const Eigen::Vector3d mean = sum / static_cast<double>(n);
  const Eigen::Matrix3d cov = outer / static_cast<double>(n) - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d normal = eig.eigenvectors().col(0);  // smallest eigenvalue first
  return normal.dot(a) < 0.0 ? Eigen::Vector3d(-normal) : normal;
}

double model_distance(const Drawing& drawing, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const DrawnBore& b : drawing.bores) {
    const BoreSurface s = bore_surface(b);
    const Eigen::Vector3d d = p - b.entrance;
    const double t = d.dot(s.axis);
    const double f = surface_residual(s, p);  // > 0 in the material
    const Eigen::Vector3d n = b.plane_normal.norm() > 0.0 ? b.plane_normal.normalized() : s.axis;
    const double plane = std::abs(d.dot(n));
    // The wall only below the entrance, the plane only outside the hole.
    const double wall = t <= 0.0 ? std::abs(f) : std::hypot(f, t);
    best = std::min(best, f >= 0.0 ? std::min(wall, plane) : wall);
  }
  for (const DrawnPart& part : drawing.parts) {
    const Eigen::Vector3d q = part.T_world_part.inverse() * p;
    const double f = inside_outside(part.shape, q);
    const double n = q.norm();
    // F(s q) = s^(2/eps1) F(q): the surface along the ray through q is at s = F^(-eps1/2).
    const double dist =
        f > 1e-12 ? n * std::abs(1.0 - std::pow(f, -0.5 * part.shape.eps1)) : part.shape.min_size();
    best = std::min(best, dist);
  }
  return best;
}

}  // namespace rangefit::render
