#include "io/bounded_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <system_error>

#include "io/io_error.hpp"

namespace rangefit::io::detail {

std::string load_file(const std::filesystem::path& path, std::size_t max_bytes,
                      bool allow_special) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw IoError(path, std::string("cannot open for reading: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw IoError(path, "cannot stat");
  if (S_ISDIR(st.st_mode)) throw IoError(path, "is a directory, not a file");
  const bool regular = S_ISREG(st.st_mode);
  if (!regular && !allow_special) {
    throw IoError(path, "is not a regular file (a device, FIFO or socket)");
  }
  if (regular && static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    throw IoError(path, "is " + std::to_string(st.st_size) + " bytes, more than the limit of " +
                            std::to_string(max_bytes));
  }
  if (!regular) {
    // A pipe or device read on purpose: blocking reads from here on, stopped at the cap.
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  }
  std::string bytes;
  if (regular) bytes.reserve(static_cast<std::size_t>(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(path, std::string("read failed: ") + std::strerror(errno));
    }
    if (n == 0) break;
    if (static_cast<std::size_t>(n) > max_bytes - bytes.size()) {
      throw IoError(path, "more than the limit of " + std::to_string(max_bytes) + " bytes");
    }
    bytes.append(buf, static_cast<std::size_t>(n));
  }
  return bytes;
}

void save_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError(path, "cannot open for writing");
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.flush();
  if (!out) throw IoError(path, "write failed (disk full?)");
}

std::optional<std::string_view> BoundedReader::next_line(std::size_t max_length) {
  if (at_end()) return std::nullopt;
  const std::size_t end = data_.find('\n', pos_);
  const std::size_t stop = end == std::string_view::npos ? data_.size() : end;
  if (stop - pos_ > max_length) {
    last_line_ = pos_line_;
    fail_at_line("line longer than " + std::to_string(max_length) + " bytes");
  }
  std::string_view line = data_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end == std::string_view::npos ? data_.size() : end + 1;
  last_line_ = pos_line_;
  ++pos_line_;
  return line;
}

std::optional<std::string_view> BoundedReader::next_token() {
  auto is_space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  };
  while (pos_ < data_.size() && is_space(data_[pos_])) {
    if (data_[pos_] == '\n') ++pos_line_;
    ++pos_;
  }
  if (at_end()) return std::nullopt;
  const std::size_t start = pos_;
  while (pos_ < data_.size() && !is_space(data_[pos_])) {
    ++pos_;
    if (pos_ - start > kMaxToken) {
      last_line_ = pos_line_;
      fail_at_line("value longer than " + std::to_string(kMaxToken) + " bytes");
    }
  }
  last_line_ = pos_line_;
  return data_.substr(start, pos_ - start);
}

std::string_view BoundedReader::take(std::size_t n, std::string_view what) {
  if (n > remaining()) {
    fail_at_byte("truncated: " + std::string(what) + " needs " + std::to_string(n) +
                 " bytes, only " + std::to_string(remaining()) + " left");
  }
  std::string_view bytes = data_.substr(pos_, n);
  pos_ += n;
  return bytes;
}

void BoundedReader::fail(std::string_view problem) const { throw IoError(file_, problem); }

void BoundedReader::fail_at_line(std::string_view problem) const {
  throw IoError(file_, "line " + std::to_string(last_line_) + ": " + std::string(problem));
}

void BoundedReader::fail_at_byte(std::string_view problem) const {
  throw IoError(file_, "byte " + std::to_string(pos_) + ": " + std::string(problem));
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  auto is_space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
  };
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

bool parse_int64(std::string_view token, std::int64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

std::string printable(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;  // hostile headers may carry megabyte words
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (text.size() > kMaxShown) out += "...";
  return out + "'";
}

}  // namespace rangefit::io::detail
