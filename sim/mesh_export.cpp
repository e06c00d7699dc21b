#include "sim/mesh_export.hpp"

#include "io/shape_mesh.hpp"

namespace rangefit::sim {

io::TriangleMesh tessellate(const Shape& shape, int rings, int segments) {
  if (rings < 2 || segments < 3) return {};
  if (const auto* p = std::get_if<PlaneShape>(&shape)) {
    return io::plane_mesh(p->size_x_mm, p->size_y_mm);
  }
  if (const auto* b = std::get_if<BoxShape>(&shape)) return io::box_mesh(b->size_mm);
  if (const auto* c = std::get_if<CylinderShape>(&shape)) {
    return io::cylinder_mesh(c->radius_mm, c->height_mm, segments);
  }
  if (const auto* s = std::get_if<SphereShape>(&shape)) {
    return io::sphere_mesh(s->radius_mm, rings, segments);
  }
  if (const auto* q = std::get_if<SuperquadricShape>(&shape)) {
    return io::superquadric_mesh(q->model, rings, segments);
  }
  return std::get<MeshShape>(shape).mesh;
}

}  // namespace rangefit::sim
