#pragma once
// Triangle meshes of analytic shapes, in the shape's own frame, outward facing and closed (except
// the plane): the simulator's primitives for STL export (sim/mesh_export.hpp) and the fitted
// parts drawn for rviz (rt/rangefit/markers).

#include <Eigen/Core>

#include "detect/object/superquadric.hpp"
#include "io/triangle_mesh.hpp"

namespace rangefit::io {

// Superquadric (eq. 2.14, tapered by eq. 2.19-2.21) and sphere on a latitude/longitude grid of
// `rings` x `segments`, one vertex per pole. Empty when rings < 2 or segments < 3.
TriangleMesh superquadric_mesh(const Superquadric& sq, int rings, int segments);
TriangleMesh sphere_mesh(double radius_mm, int rings, int segments);
// Cylinder about z, z in [-height/2, height/2], with `segments` sides and both caps (each cap
// triangle has the vertex on the axis). Empty when segments < 3.
TriangleMesh cylinder_mesh(double radius_mm, double height_mm, int segments);
// Box centred at the origin; plane in z = 0 (two triangles facing +z).
TriangleMesh box_mesh(const Eigen::Vector3d& size_mm);
TriangleMesh plane_mesh(double size_x_mm, double size_y_mm);

}  // namespace rangefit::io
