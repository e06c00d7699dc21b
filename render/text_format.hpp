#pragma once
// printf-style formatting of the short labels drawn into pictures (numbers with units).

#include <cstdio>
#include <string>

namespace rangefit::render {

// At most 255 characters; a longer label is cut.
inline std::string format(const char* fmt, auto... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, args...);
  return buffer;
}

}  // namespace rangefit::render
