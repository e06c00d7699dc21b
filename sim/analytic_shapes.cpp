#include "sim/analytic_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/superquadric_adapter.hpp"

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;

struct LocalHit {
  double t;
  Vector3d normal;
};

// Smallest root of a t^2 + 2 b t + c = 0 inside (t_min, t_max] that passes accept().
template <class Accept>
std::optional<double> quadratic_root(double a, double b, double c, double t_min, double t_max,
                                     Accept accept) {
  if (a <= 0.0) return std::nullopt;
  const double disc = b * b - a * c;
  if (disc < 0.0) return std::nullopt;
  const double s = std::sqrt(disc);
  // Numerically stable pair of roots.
  const double q = b >= 0.0 ? -(b + s) : -(b - s);
  double t0 = q / a;
  double t1 = q != 0.0 ? c / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  for (double t : {t0, t1}) {
    if (t > t_min && t <= t_max && accept(t)) return t;
  }
  return std::nullopt;
}

std::optional<LocalHit> hit_plane(const PlaneShape& s, const Vector3d& o, const Vector3d& d,
                                  double t_min, double t_max) {
  if (d.z() == 0.0) return std::nullopt;
  const double t = -o.z() / d.z();
  if (!(t > t_min && t <= t_max)) return std::nullopt;
  const Vector3d p = o + t * d;
  if (std::abs(p.x()) > 0.5 * s.size_x_mm || std::abs(p.y()) > 0.5 * s.size_y_mm) {
    return std::nullopt;
  }
  return LocalHit{t, Vector3d::UnitZ()};
}

std::optional<LocalHit> hit_box(const BoxShape& s, const Vector3d& o, const Vector3d& d,
                                double t_min, double t_max) {
  // Slab method; remember which slab gave the entry and exit.
  double t_enter = -std::numeric_limits<double>::infinity();
  double t_exit = std::numeric_limits<double>::infinity();
  int enter_axis = -1, exit_axis = -1;
  for (int i = 0; i < 3; ++i) {
    const double h = 0.5 * s.size_mm[i];
    if (d[i] == 0.0) {
      if (std::abs(o[i]) > h) return std::nullopt;
      continue;
    }
    double t0 = (-h - o[i]) / d[i];
    double t1 = (h - o[i]) / d[i];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_enter) t_enter = t0, enter_axis = i;
    if (t1 < t_exit) t_exit = t1, exit_axis = i;
  }
  if (t_enter > t_exit) return std::nullopt;
  if (t_enter > t_min && t_enter <= t_max && enter_axis >= 0) {
    Vector3d n = Vector3d::Zero();
    n[enter_axis] = d[enter_axis] > 0.0 ? -1.0 : 1.0;
    return LocalHit{t_enter, n};
  }
  if (t_exit > t_min && t_exit <= t_max && exit_axis >= 0) {  // ray starts inside
    Vector3d n = Vector3d::Zero();
    n[exit_axis] = d[exit_axis] > 0.0 ? 1.0 : -1.0;
    return LocalHit{t_exit, n};
  }
  return std::nullopt;
}

std::optional<LocalHit> hit_cylinder(const CylinderShape& s, const Vector3d& o, const Vector3d& d,
                                     double t_min, double t_max) {
  std::optional<LocalHit> best;
  const double r2 = s.radius_mm * s.radius_mm;
  const auto side = quadratic_root(d.x() * d.x() + d.y() * d.y(), o.x() * d.x() + o.y() * d.y(),
                                   o.x() * o.x() + o.y() * o.y() - r2, t_min, t_max, [&](double t) {
                                     return std::abs(o.z() + t * d.z()) <= 0.5 * s.height_mm;
                                   });
  if (side) {
    const Vector3d p = o + *side * d;
    best = LocalHit{*side, Vector3d(p.x(), p.y(), 0.0).normalized()};
  }
  if (d.z() != 0.0) {
    for (double zc : {-0.5 * s.height_mm, 0.5 * s.height_mm}) {
      const double t = (zc - o.z()) / d.z();
      if (!(t > t_min && t <= t_max) || (best && t >= best->t)) continue;
      const Vector3d p = o + t * d;
      if (p.x() * p.x() + p.y() * p.y() > r2) continue;
      best = LocalHit{t, Vector3d(0.0, 0.0, zc < 0.0 ? -1.0 : 1.0)};
    }
  }
  return best;
}

std::optional<LocalHit> hit_sphere(const SphereShape& s, const Vector3d& o, const Vector3d& d,
                                   double t_min, double t_max) {
  const auto t =
      quadratic_root(d.squaredNorm(), o.dot(d), o.squaredNorm() - s.radius_mm * s.radius_mm, t_min,
                     t_max, [](double) { return true; });
  if (!t) return std::nullopt;
  return LocalHit{*t, (o + *t * d).normalized()};
}

double box_distance(const BoxShape& s, const Vector3d& p) {
  const Vector3d q = p.cwiseAbs() - 0.5 * s.size_mm;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return std::abs(outside + inside);
}

double cylinder_distance(const CylinderShape& s, const Vector3d& p) {
  const Eigen::Vector2d q(std::hypot(p.x(), p.y()) - s.radius_mm,
                          std::abs(p.z()) - 0.5 * s.height_mm);
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return std::abs(outside + inside);
}

}  // namespace

std::optional<ShapeHit> intersect_shape(const Shape& shape, const Eigen::Isometry3d& T_world_object,
                                        const Vector3d& origin, const Vector3d& dir, double t_min,
                                        double t_max) {
  const Eigen::Isometry3d T_object_world = T_world_object.inverse();
  const Vector3d o = T_object_world * origin;
  const Vector3d d = T_object_world.linear() * dir;
  std::optional<LocalHit> local;
  if (const auto* p = std::get_if<PlaneShape>(&shape)) local = hit_plane(*p, o, d, t_min, t_max);
  if (const auto* b = std::get_if<BoxShape>(&shape)) local = hit_box(*b, o, d, t_min, t_max);
  if (const auto* c = std::get_if<CylinderShape>(&shape))
    local = hit_cylinder(*c, o, d, t_min, t_max);
  if (const auto* s = std::get_if<SphereShape>(&shape)) local = hit_sphere(*s, o, d, t_min, t_max);
  if (const auto* q = std::get_if<SuperquadricShape>(&shape)) {
    return intersect_superquadric_shape(*q, T_world_object, origin, dir, t_min, t_max);
  }
  if (!local) return std::nullopt;
  return ShapeHit{local->t, (T_world_object.linear() * local->normal).normalized()};
}

double surface_distance(const Shape& shape, const Eigen::Isometry3d& T_world_object,
                        const Vector3d& p_world) {
  const Vector3d p = T_world_object.inverse() * p_world;
  if (const auto* pl = std::get_if<PlaneShape>(&shape)) {
    const double dx = std::max(std::abs(p.x()) - 0.5 * pl->size_x_mm, 0.0);
    const double dy = std::max(std::abs(p.y()) - 0.5 * pl->size_y_mm, 0.0);
    return std::sqrt(dx * dx + dy * dy + p.z() * p.z());
  }
  if (const auto* b = std::get_if<BoxShape>(&shape)) return box_distance(*b, p);
  if (const auto* c = std::get_if<CylinderShape>(&shape)) return cylinder_distance(*c, p);
  if (const auto* s = std::get_if<SphereShape>(&shape)) return std::abs(p.norm() - s->radius_mm);
  return std::numeric_limits<double>::quiet_NaN();
}

Eigen::AlignedBox3d local_bounds(const Shape& shape) {
  Eigen::AlignedBox3d box;
  if (const auto* pl = std::get_if<PlaneShape>(&shape)) {
    const Vector3d h(0.5 * pl->size_x_mm, 0.5 * pl->size_y_mm, 0.0);
    box.extend(-h);
    box.extend(h);
  } else if (const auto* b = std::get_if<BoxShape>(&shape)) {
    box.extend(-0.5 * b->size_mm);
    box.extend(0.5 * b->size_mm);
  } else if (const auto* c = std::get_if<CylinderShape>(&shape)) {
    box.extend(Vector3d(-c->radius_mm, -c->radius_mm, -0.5 * c->height_mm));
    box.extend(Vector3d(c->radius_mm, c->radius_mm, 0.5 * c->height_mm));
  } else if (const auto* s = std::get_if<SphereShape>(&shape)) {
    box.extend(Vector3d::Constant(-s->radius_mm));
    box.extend(Vector3d::Constant(s->radius_mm));
  } else if (const auto* q = std::get_if<SuperquadricShape>(&shape)) {
    box = part_bounds(q->model);
  } else if (const auto* m = std::get_if<MeshShape>(&shape)) {
    for (const auto& v : m->mesh.vertices) box.extend(v);
  }
  return box;
}

std::optional<double> intersect_triangle(const Vector3d& a, const Vector3d& b, const Vector3d& c,
                                         const Vector3d& origin, const Vector3d& dir, double t_min,
                                         double t_max) {
  const Vector3d e1 = b - a;
  const Vector3d e2 = c - a;
  const Vector3d pv = dir.cross(e2);
  const double det = e1.dot(pv);
  if (std::abs(det) < 1e-300) return std::nullopt;
  const double inv = 1.0 / det;
  const Vector3d tv = origin - a;
  const double u = tv.dot(pv) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Vector3d qv = tv.cross(e1);
  const double v = dir.dot(qv) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = e2.dot(qv) * inv;
  if (!(t > t_min && t <= t_max)) return std::nullopt;
  return t;
}

}  // namespace rangefit::sim
