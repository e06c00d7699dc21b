#pragma once
// A triangle mesh as read from STL or generated for simulated scenes. Positions in mm.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace rangefit::io {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;                // mm
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
};

}  // namespace rangefit::io
