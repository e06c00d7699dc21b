#pragma once
// Triangle meshes of the scene's analytic primitives, for shipping scenes as STL files (example
// scenes built from small STL files) and for checking the STL path against the exact
// primitives. Meshes are in the object frame, outward facing, closed except for planes.

#include "io/triangle_mesh.hpp"
#include "sim/scene.hpp"

namespace rangefit::sim {

// Tessellates a shape: superquadrics and spheres on a latitude/longitude grid of `rings` x
// `segments` (eq. 2.14 with the tapering of eq. 2.19-2.21), cylinders with `segments` sides,
// boxes and planes exactly. A MeshShape is returned as it is. Empty mesh when rings < 2 or
// segments < 3.
io::TriangleMesh tessellate(const Shape& shape, int rings, int segments);

}  // namespace rangefit::sim
