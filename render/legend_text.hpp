#pragma once
// Text of a picture's legend: printf-style lines and "x, y, z" vectors in mm with 3 decimals,
// shared by every caller that writes a legend (the CLI's render and the service's pictures).

#include <Eigen/Core>
#include <cstdio>
#include <string>

namespace rangefit::render {

// One legend line; longer than 255 characters is cut off.
inline std::string legend_format(const char* fmt, auto... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, args...);
  return buffer;
}

inline std::string legend_vector(const Eigen::Vector3d& v) {
  return legend_format("%.3f, %.3f, %.3f", v.x(), v.y(), v.z());
}

}  // namespace rangefit::render
