#pragma once
// STL meshes (CAD models of the objects and the cell). Positions in the file are taken as mm.

#include <filesystem>

#include "io/io_error.hpp"
#include "io/triangle_mesh.hpp"

namespace rangefit::io {

// Reads binary or ASCII STL. Binary is recognised by its size (84 + 50 * triangle count bytes), so
// binary files whose 80-byte header starts with "solid" load too. Identical vertices (bit-equal
// after conversion to double, -0 == +0) are merged into one. Throws IoError on anything malformed,
// truncated or non-finite.
TriangleMesh read_stl(const std::filesystem::path& path);

// Writes binary STL (little endian, float32, facet normals from the vertex order). Throws IoError
// when a triangle refers to a missing vertex or the file cannot be written.
void write_stl(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace rangefit::io
