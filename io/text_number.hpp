#pragma once
// Shortest text that reads back to the same double or float (std::to_chars), for the ASCII
// writers.

#include <charconv>
#include <cstdint>
#include <string>

namespace rangefit::io::detail {

inline void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

inline void append_number(std::string& out, float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

inline void append_number(std::string& out, std::int64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

inline std::string number_text(double value) {
  std::string out;
  append_number(out, value);
  return out;
}

}  // namespace rangefit::io::detail
