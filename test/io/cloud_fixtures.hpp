#pragma once
// Clouds with every optional part filled in, shared by the PLY, PCD and fuzz tests.

#include <cstdint>
#include <cstring>
#include <string>

#include "detect/common/point_cloud.hpp"

namespace rangefit::io::test {

// A 3 x 4 organised scan, row-major, with cells (0,1) and (2,3) empty; normals and stamps set,
// including a negative stamp and one above 2^32 ns.
inline PointCloud organised_cloud() {
  PointCloud cloud;
  cloud.frame_id = "css_scan";
  cloud.grid.rows = 3;
  cloud.grid.cols = 4;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      if ((r == 0 && c == 1) || (r == 2 && c == 3)) {
        cloud.grid.index.push_back(-1);
        continue;
      }
      cloud.grid.index.push_back(static_cast<std::int32_t>(cloud.points.size()));
      cloud.points.emplace_back(0.1 * c + 1e-9, -2.5 * r, 1000.0 / 3.0 + r * c);
      cloud.normals.push_back(Eigen::Vector3d(r, c, 1.0).normalized());
      cloud.stamps.emplace_back(std::int64_t{1} << 40 | (r * 4 + c) * 1234567LL);
    }
  }
  cloud.stamps[1] = std::chrono::nanoseconds(-5);
  return cloud;
}

template <typename T>
void append_le(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // the test machines are little endian (x86-64, arm64)
  out.append(bytes, sizeof(T));
}

}  // namespace rangefit::io::test
