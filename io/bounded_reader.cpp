#include "io/bounded_reader.hpp"

#include <charconv>
#include <fstream>
#include <system_error>

#include "io/io_error.hpp"

namespace rangefit::io::detail {

std::string load_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path, "cannot open for reading");
  std::string bytes;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size > 0) {
    bytes.resize(static_cast<std::size_t>(size));
    in.read(bytes.data(), size);
    if (in.gcount() != size) throw IoError(path, "read failed (file changed while reading?)");
  } else {
    // Size unknown (pipe, /proc file): read what there is.
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
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
