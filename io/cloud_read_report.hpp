#pragma once
// What a point-cloud reader saw besides the points it returns.

#include <cstddef>
#include <string>
#include <vector>

namespace rangefit::io {

struct CloudReadReport {
  std::size_t points_in_file = 0;      // points declared and read, before dropping
  std::size_t non_finite_dropped = 0;  // points with a NaN/Inf position or normal, not returned
  // Properties (PLY) or fields (PCD) present in the file but not used. PLY vertex properties are
  // listed by name ("red"), properties of other elements as "element.property"
  // ("face.vertex_indices").
  std::vector<std::string> ignored_properties;
};

}  // namespace rangefit::io
