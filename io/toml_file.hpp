#pragma once
// The one way rangefit reads TOML (daemon config, [fusion], scenes, object models). toml++ is a
// recursive-descent parser: a key of tens of thousands of dotted segments or a deeply nested
// array exhausts the stack (SIGSEGV, no exception), and a few non-ASCII bytes where a key is
// expected reach TOML_UNREACHABLE in 3.3 (undefined behaviour). So before toml++ sees the text,
// a cheap linear scan checks what recursion depends on and what TOML allows outside strings:
// valid UTF-8, ASCII outside strings and comments, at most kMaxTomlKeySegments dotted key
// segments and kMaxTomlDepth open brackets/braces. Files are read as regular files only, with a
// size cap, so /dev/zero, a FIFO or a directory is an error instead of a hang or bad_alloc.
//
// Errors are TomlError (an IoError) with what() = "<source>:<line>: <problem>", the format of
// every loader.

#include <toml++/toml.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "io/io_error.hpp"

namespace rangefit::io {

inline constexpr std::size_t kMaxTomlBytes = 1 << 20;   // every rangefit TOML file is a few KB
inline constexpr std::size_t kMaxTomlKeySegments = 32;  // a.b.c ... in one key or table header
inline constexpr std::size_t kMaxTomlDepth = 32;        // nested [ and { (arrays, inline tables)

class TomlError : public IoError {
 public:
  TomlError(std::string_view source, std::uint32_t line, std::string_view problem);
  std::uint32_t line() const { return line_; }  // 1-based; 0 when not tied to a line
  const std::string& problem() const { return problem_; }

 private:
  std::uint32_t line_;
  std::string problem_;
};

struct TomlTextProblem {
  std::uint32_t line = 0;  // 1-based
  std::string problem;
};

// The pre-scan alone: nullopt when toml++ may safely parse the text.
std::optional<TomlTextProblem> check_toml_text(std::string_view text);

// Pre-scan, then toml++; every failure throws TomlError naming source and line.
toml::table parse_toml(std::string_view text, std::string_view source);

// The bytes of a TOML file: a regular file (opened without blocking, so a FIFO cannot hang us) of
// at most max_bytes. Throws TomlError (line 0) when it is not.
std::string read_toml_file(const std::filesystem::path& path,
                           std::size_t max_bytes = kMaxTomlBytes);

}  // namespace rangefit::io
