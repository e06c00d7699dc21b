#pragma once
// The one exception type of io/. Readers and writers throw it for every problem with a file:
// cannot open, malformed, truncated, hostile counts, unsupported variants. The message always
// starts with the file name, then says where (header, line N or byte N) and what went wrong, so a
// user can act on it without a debugger.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rangefit::io {

class IoError : public std::runtime_error {
 public:
  IoError(const std::filesystem::path& file, std::string_view problem)
      : std::runtime_error(file.string() + ": " + std::string(problem)), file_(file) {}
  // "<file>:<line>: <problem>" for text formats whose errors point at a line (0: no line).
  IoError(const std::filesystem::path& file, std::uint32_t line, std::string_view problem)
      : std::runtime_error(at_line(file, line, problem)), file_(file) {}

  const std::filesystem::path& file() const { return file_; }

 private:
  static std::string at_line(const std::filesystem::path& file, std::uint32_t line,
                             std::string_view problem) {
    std::string out = file.string();
    if (line > 0) out.append(":").append(std::to_string(line));
    return out.append(": ").append(problem);
  }

  std::filesystem::path file_;
};

}  // namespace rangefit::io
