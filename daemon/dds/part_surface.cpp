#include "daemon/dds/part_surface.hpp"

#include <algorithm>

#include "io/shape_mesh.hpp"

namespace rangefit::daemon {
namespace {

// Latitude rings and longitude segments of the tessellation: ~0.3 mm chord error on a 50 mm
// part, 720 triangles per superquadric part (52 kB on the wire).
constexpr int kRings = 16, kSegments = 24, kBoreSegments = 32;

PartSurface bore_surface(double r) {
  const double depth = drawn_bore_depth_mm(r);
  io::TriangleMesh cylinder = io::cylinder_mesh(r, depth, kBoreSegments);
  // The cylinder mesh is closed; a bore is open at both ends, so the cap triangles (those
  // with a vertex on the axis) go, and the tube moves from z in [-d/2, d/2] to [-d, 0].
  PartSurface s;
  s.mesh.vertices = cylinder.vertices;
  for (auto& v : s.mesh.vertices) v.z() -= 0.5 * depth;
  for (const auto& t : cylinder.triangles) {
    const bool on_axis = std::any_of(t.begin(), t.end(), [&](std::uint32_t i) {
      return cylinder.vertices[i].head<2>().norm() < 0.5 * r;
    });
    if (!on_axis) s.mesh.triangles.push_back(t);
  }
  return s;
}

std::optional<PartSurface> shape_of(const DetectionResult& result, const PartPose& part,
                                    const std::map<std::string, ObjectModel>& models) {
  if (result.kind == DetectKind::kBore) {
    if (!(result.bore_radius_mm > 0)) return std::nullopt;
    return bore_surface(result.bore_radius_mm);
  }
  const auto model = models.find(result.model);
  if (model == models.end()) return std::nullopt;
  for (const ModelPart& p : model->second.parts) {
    if (p.name != part.name || !p.shape.valid()) continue;
    PartSurface s;
    s.mesh = io::superquadric_mesh(p.shape, kRings, kSegments);
    return s;
  }
  return std::nullopt;
}

}  // namespace

double drawn_bore_depth_mm(double radius_mm) { return 2.0 * radius_mm; }

std::optional<PartSurface> part_surface(const DetectionResult& result, const PartPose& part,
                                        const std::map<std::string, ObjectModel>& models) {
  std::optional<PartSurface> s = shape_of(result, part, models);
  // The box of the drawn vertices: the grid holds the equator, the poles and the longitudes 0,
  // +-pi/2 and pi, so it reaches an untapered part's extremes (a taper's by the chord error).
  if (s) {
    for (const auto& v : s->mesh.vertices) s->extent.extend(v);
  }
  return s;
}

}  // namespace rangefit::daemon
