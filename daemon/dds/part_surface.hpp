#pragma once
// The fitted surface of a detected part as rviz draws it and vision_msgs boxes it: a triangle
// mesh in the part's frame and the part's extent there. A bore is its wall, an open tube from the
// entrance (the part frame's origin, z out of the bore) into the part; an object part is its
// tapered superquadric (thesis eq. 2.14, 2.19-2.21), tessellated as the simulator does
// (sim/mesh_export.hpp).

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>

#include "daemon/service/scan_types.hpp"
#include "detect/object/object_model.hpp"
#include "io/triangle_mesh.hpp"

namespace rangefit::daemon {

struct PartSurface {
  io::TriangleMesh mesh;       // part frame, mm, counter-clockwise seen from outside
  Eigen::AlignedBox3d extent;  // part frame, mm: the box of the mesh's vertices
};

// How far a bore's wall is drawn into the part: a result does not say how deep the scan saw it,
// so two radii, as the renderer draws a bore whose wall the scan does not show.
double drawn_bore_depth_mm(double radius_mm);

// The surface of `part` of `result`: the bore of radius result.bore_radius_mm, or the part of the
// result's model in `models` (by model name). nullopt when the shape is unknown (a model or part
// not in `models`, a bore without radius).
std::optional<PartSurface> part_surface(const DetectionResult& result, const PartPose& part,
                                        const std::map<std::string, ObjectModel>& models);

}  // namespace rangefit::daemon
