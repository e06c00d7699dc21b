#pragma once
// The line splitting and number reading the calibration text formats share
// (calib/raw_sweep_text.hpp, calib/css_scan_text.hpp).

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace rangefit::calib::text_fields {

// Words of a line, split at blanks and tabs (a trailing '\r' is a blank).
inline std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

// A whole word as a finite number.
inline bool number(std::string_view w, double& v) {
  const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
  return r.ec == std::errc() && r.ptr == w.data() + w.size() && std::isfinite(v);
}

// Cuts the next line off `text` ('#' starts a comment).
inline std::string_view next_line(std::string_view& text) {
  const std::size_t end = text.find('\n');
  std::string_view line = text.substr(0, end);
  text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
  if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
    line = line.substr(0, hash);
  }
  return line;
}

// Reads a text format of a header line and record lines: `header(words)` on the first line that
// has words, `record(words)` on each later one; each returns an error message, empty when the
// line is good. Returns "SOURCE:LINE: message" for the first bad line, `no_header` when there is
// no line at all, else an empty string.
template <class Header, class Record>
std::string read_lines(std::string_view text, std::string_view source, const char* no_header,
                       Header&& header, Record&& record) {
  bool have_header = false;
  std::size_t line_no = 0;
  std::string error;
  while (error.empty() && !text.empty()) {
    const auto w = words(next_line(text));
    ++line_no;
    if (w.empty()) continue;
    error = have_header ? record(w) : header(w);
    have_header = true;
  }
  if (error.empty() && !have_header) error = no_header;
  return error.empty() ? error
                       : std::string(source) + ":" + std::to_string(line_no) + ": " + error;
}

}  // namespace rangefit::calib::text_fields
