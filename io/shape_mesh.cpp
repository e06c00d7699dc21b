#include "io/shape_mesh.hpp"

#include <cmath>
#include <numbers>

namespace rangefit::io {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

std::uint32_t add(TriangleMesh& m, const Vector3d& v) {
  m.vertices.push_back(v);
  return static_cast<std::uint32_t>(m.vertices.size() - 1);
}

// A closed surface given as point(latitude in [-pi/2, pi/2], longitude): one vertex per pole,
// counter-clockwise seen from outside.
template <class Point>
TriangleMesh lat_long(int rings, int segments, Point point) {
  TriangleMesh m;
  const std::uint32_t south = add(m, point(-0.5 * kPi, 0.0));
  std::vector<std::uint32_t> row_start;
  for (int r = 1; r < rings; ++r) {
    row_start.push_back(static_cast<std::uint32_t>(m.vertices.size()));
    const double eta = -0.5 * kPi + kPi * r / rings;
    for (int s = 0; s < segments; ++s) add(m, point(eta, -kPi + 2.0 * kPi * s / segments));
  }
  const std::uint32_t north = add(m, point(0.5 * kPi, 0.0));
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::uint32_t s = 0; s < n; ++s) {
    const std::uint32_t s1 = (s + 1) % n;
    m.triangles.push_back({south, row_start.front() + s1, row_start.front() + s});
    m.triangles.push_back({north, row_start.back() + s, row_start.back() + s1});
    for (std::size_t r = 0; r + 1 < row_start.size(); ++r) {
      const std::uint32_t a = row_start[r], b = row_start[r + 1];
      m.triangles.push_back({a + s, a + s1, b + s1});
      m.triangles.push_back({a + s, b + s1, b + s});
    }
  }
  return m;
}

TriangleMesh box(const Vector3d& size) {
  TriangleMesh m;
  const Vector3d h = 0.5 * size;
  for (int i = 0; i < 8; ++i) {
    add(m, Vector3d((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
  }
  // Faces as quads of corner indices, counter-clockwise from outside.
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

TriangleMesh cylinder(double r, double height, int segments) {
  TriangleMesh m;
  const double h = 0.5 * height;
  const std::uint32_t bottom = add(m, Vector3d(0, 0, -h)), top = add(m, Vector3d(0, 0, h));
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::uint32_t s = 0; s < n; ++s) {
    const double a = 2.0 * kPi * s / n;
    add(m, Vector3d(r * std::cos(a), r * std::sin(a), -h));
    add(m, Vector3d(r * std::cos(a), r * std::sin(a), h));
  }
  for (std::uint32_t s = 0; s < n; ++s) {
    const std::uint32_t b0 = 2 + 2 * s, t0 = b0 + 1, b1 = 2 + 2 * ((s + 1) % n), t1 = b1 + 1;
    m.triangles.push_back({b0, b1, t1});
    m.triangles.push_back({b0, t1, t0});
    m.triangles.push_back({bottom, b1, b0});
    m.triangles.push_back({top, t0, t1});
  }
  return m;
}

}  // namespace

TriangleMesh superquadric_mesh(const Superquadric& sq, int rings, int segments) {
  if (rings < 2 || segments < 3) return {};
  return lat_long(rings, segments,
                  [&sq](double eta, double omega) { return surface_point(sq, eta, omega); });
}

TriangleMesh sphere_mesh(double r, int rings, int segments) {
  if (rings < 2 || segments < 3) return {};
  return lat_long(rings, segments, [r](double eta, double omega) {
    return Vector3d(r * std::cos(eta) * std::cos(omega), r * std::cos(eta) * std::sin(omega),
                    r * std::sin(eta));
  });
}

TriangleMesh cylinder_mesh(double radius_mm, double height_mm, int segments) {
  if (segments < 3) return {};
  return cylinder(radius_mm, height_mm, segments);
}

TriangleMesh box_mesh(const Eigen::Vector3d& size_mm) { return box(size_mm); }

TriangleMesh plane_mesh(double size_x_mm, double size_y_mm) {
  TriangleMesh m;
  const double hx = 0.5 * size_x_mm, hy = 0.5 * size_y_mm;
  add(m, Vector3d(-hx, -hy, 0)), add(m, Vector3d(hx, -hy, 0));
  add(m, Vector3d(hx, hy, 0)), add(m, Vector3d(-hx, hy, 0));
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

}  // namespace rangefit::io
