#pragma once
// Reading untrusted files safely. The whole file is loaded first, so every count a header declares
// can be checked against the bytes that remain before anything is reserved: no allocation is ever
// larger than the file can justify. Every failure throws IoError naming the file and the position.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rangefit::io::detail {

inline constexpr std::size_t kMaxHeaderLine = 64 * 1024;  // bytes; longer header lines are hostile
inline constexpr std::size_t kMaxToken = 128;             // bytes; no number needs more

// Clouds and meshes larger than this are refused: 2 GiB is ~100 M points, far more than any
// scan, and a bound on what a hostile path (a huge sparse file) can make us allocate.
inline constexpr std::size_t kMaxFileBytes = std::size_t{2} << 30;

// Reads the whole file; throws IoError when it cannot be opened or read, is a directory, is
// larger than max_bytes or is not a regular file. The file is opened with O_NONBLOCK, so a FIFO
// without a writer cannot block us; devices and pipes (/dev/zero, a FIFO) are refused unless
// allow_special, and then read only up to max_bytes.
std::string load_file(const std::filesystem::path& path, std::size_t max_bytes = kMaxFileBytes,
                      bool allow_special = false);
// Writes bytes to the file (replacing it); throws IoError on failure.
void save_file(const std::filesystem::path& path, std::string_view bytes);

class BoundedReader {
 public:
  BoundedReader(const std::filesystem::path& file, std::string_view data)
      : file_(file), data_(data) {}

  const std::filesystem::path& file() const { return file_; }
  std::string_view data() const { return data_; }
  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return data_.size() - pos_; }
  bool at_end() const { return pos_ >= data_.size(); }
  int line() const { return last_line_; }  // 1-based line of the last line or token returned

  // Next text line without its "\n" or "\r\n"; nullopt at the end of the data. Throws when the
  // line is longer than max_length.
  std::optional<std::string_view> next_line(std::size_t max_length = kMaxHeaderLine);
  // Next whitespace-separated token; nullopt at the end of the data. Throws past kMaxToken.
  std::optional<std::string_view> next_token();
  // Exactly n raw bytes; throws "truncated" naming `what` when fewer remain.
  std::string_view take(std::size_t n, std::string_view what);

  [[noreturn]] void fail(std::string_view problem) const;          // "<file>: <problem>"
  [[noreturn]] void fail_at_line(std::string_view problem) const;  // "<file>: line N: ..."
  [[noreturn]] void fail_at_byte(std::string_view problem) const;  // "<file>: byte N: ..."

 private:
  std::filesystem::path file_;
  std::string_view data_;
  std::size_t pos_ = 0;
  int pos_line_ = 1;   // line the read position is on
  int last_line_ = 0;  // line of the last item returned
};

// Whitespace-separated words of a header line (spaces, tabs, a stray '\r').
std::vector<std::string_view> split_words(std::string_view line);
// Strict number parsing of a whole token; false on anything else (sign rules as std::from_chars,
// plus an optional leading '+'). Doubles accept nan/inf as PCL writes them.
bool parse_double(std::string_view token, double& value);
bool parse_int64(std::string_view token, std::int64_t& value);

// Untrusted text for a message: quoted, non-printables replaced, cut after 40 characters.
std::string printable(std::string_view text);

}  // namespace rangefit::io::detail
