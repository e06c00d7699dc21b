#include "io/toml_file.hpp"

#include "io/bounded_reader.hpp"
#include "io/io_error.hpp"

namespace rangefit::io {
namespace {

// Length of the UTF-8 sequence starting at text[i], 0 when it is not valid (overlong forms,
// surrogates and code points above U+10FFFF included, as toml++ assumes they never occur).
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t n = 0;
  std::uint32_t cp = 0;
  if (b0 >= 0xc2 && b0 <= 0xdf) {
    n = 2, cp = b0 & 0x1fu;
  } else if (b0 >= 0xe0 && b0 <= 0xef) {
    n = 3, cp = b0 & 0x0fu;
  } else if (b0 >= 0xf0 && b0 <= 0xf4) {
    n = 4, cp = b0 & 0x07u;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xc0u) != 0x80u) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3fu);
  }
  if ((n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000) || cp > 0x10ffff) return 0;
  if (cp >= 0xd800 && cp <= 0xdfff) return 0;
  return n;
}

// Where toml++ ends a bare value (a number, a date, true, or garbage).
bool value_terminator(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == ']' || c == '}' || c == ',' || c == '#';
}

bool bare_key_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '+';  // '+' only so that a float exponent does not end a chain early
}

// A linear scan that knows just enough TOML to tell strings and comments from the rest.
class PreScan {
 public:
  explicit PreScan(std::string_view text) : text_(text) {}

  std::optional<TomlTextProblem> run() {
    try {
      check_utf8();
      check_spaced_dates();
      scan();
    } catch (const TomlTextProblem& p) {
      return p;
    }
    return std::nullopt;
  }

 private:
  [[noreturn]] void fail(std::string problem) const { throw TomlTextProblem{line_, problem}; }

  void check_utf8() {
    std::uint32_t line = 1;
    for (std::size_t i = 0; i < text_.size();) {
      const std::size_t n = utf8_length(text_, i);
      if (n == 0) {
        line_ = line;
        fail("not valid UTF-8 (byte " + std::to_string(i) + ")");
      }
      // TOML allows no control character but tab and line ends anywhere, comments included
      // (escaped in strings). toml++ 3.3 reads on past a NUL in a bare value, into a comment,
      // and a U+FD9B there reached TOML_UNREACHABLE (found by test/fuzz/fusion_config_fuzz).
      const auto c = static_cast<unsigned char>(text_[i]);
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f) {
        line_ = line;
        fail("control character " + std::to_string(c) + " (byte " + std::to_string(i) + ")");
      }
      if (text_[i] == '\n') ++line;
      i += n;
    }
  }

  // Whether the characters before `end` read as toml++'s date: its last 10 characters up to
  // whitespace, any character counting but the '_' digit separators toml++ leaves out, have '-'
  // at 4 and 7 (conservative: toml++ also checks the others' traits).
  bool date_before(std::size_t end) const {
    char last[10];
    std::size_t n = 0;
    for (std::size_t k = end; k > 0 && n < 10; --k) {
      const char c = text_[k - 1];
      if (c == '_') continue;
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') break;  // '=' too counts for toml++
      last[9 - n++] = c;
    }
    return n == 10 && last[4] == '-' && last[7] == '-';
  }

  // toml++ 3.3 reads a value like 1979-05-27 followed by a space and a digit as a date-time
  // with a space for the T: it takes the digit, then the next character whatever it is (a line
  // end included), then reads on to the next whitespace testing each character for it, and its
  // whitespace table reaches TOML_UNREACHABLE for non-ASCII code points there (found by
  // test/fuzz/object_model_fuzz). None may stand there.
  void check_spaced_dates() {
    std::uint32_t line = 1;
    for (std::size_t i = 0; i < text_.size(); ++i) {
      if (text_[i] == '\n') ++line;
      if (text_[i] != ' ' || i + 1 >= text_.size() || text_[i + 1] < '0' || text_[i + 1] > '9' ||
          !date_before(i)) {
        continue;
      }
      for (std::size_t j = i + 2; j < text_.size() && j < i + 2 + 128; ++j) {
        const char c = text_[j];
        if (static_cast<unsigned char>(c) >= 0x80) {
          line_ = line;
          fail("non-ASCII character right after a date and time separated by a space");
        }
        // The character after the digit is always taken.
        if (j > i + 2 && (value_terminator(c) || c == '\r')) break;
      }
    }
  }

  void scan() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      // toml++ scans a bare value up to its terminator, testing each character for whitespace;
      // quotes and '=' inside it are no tokens.
      const bool terminator = value_terminator(c);
      if (terminator) in_bare_ = false;
      if (c == '\n') {
        ++line_;
        chain_ = 1;
        prev_ = '\n';
        if (open_.empty()) expect_key_ = true;  // a new statement (arrays may span lines)
        ++pos_;
        continue;
      }
      if (c == ' ' || c == '\t') {
        ++pos_;
        continue;
      }
      if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        continue;
      }
      if ((c == '"' || c == '\'') && !in_bare_ && starts_token()) {
        skip_string(c);  // a quoted key segment keeps the dotted chain going
        prev_ = c;
        continue;
      }
      // Anything else, including a quote inside a bare word: toml++ scans up to ~127 characters
      // of a bare value before it decides what it is, testing each for whitespace.
      if (c == '.') {
        if (++chain_ > kMaxTomlKeySegments) {
          fail("more than " + std::to_string(kMaxTomlKeySegments) + " dotted key segments");
        }
      } else if (c == '[' || c == '{') {
        if (open_.size() >= kMaxTomlDepth) {
          fail("nested deeper than " + std::to_string(kMaxTomlDepth) + " brackets or braces");
        }
        // A table header ([a] or [[a]]) holds a key; an array holds values; an inline table
        // holds keys again.
        const bool header =
            c == '[' && expect_key_ && (open_.empty() || (prev_ == '[' && open_.back() == 'h'));
        open_.push_back(c == '{' ? '{' : header ? 'h' : '[');
        expect_key_ = c == '{' || header;
        chain_ = 1;
      } else if (c == ']' || c == '}') {
        if (!open_.empty()) open_.pop_back();  // unbalanced input is toml++'s to report
        expect_key_ = false;
        chain_ = 1;
      } else if (c == '=') {
        expect_key_ = false;
        chain_ = 1;
      } else if (c == ',') {
        expect_key_ = !open_.empty() && open_.back() == '{';
        chain_ = 1;
      } else if (static_cast<unsigned char>(c) >= 0x80) {
        fail("non-ASCII character outside a string or comment");
      } else if (!bare_key_char(c) && c != '"' && c != '\'') {
        chain_ = 1;
      }
      // '=' starts a value rather than being part of one: a quote right after it opens a string
      // (x ="..."), as it does for toml++.
      if (!expect_key_ && !terminator && c != '[' && c != '{' && c != '=') in_bare_ = true;
      prev_ = c;
      ++pos_;
    }
  }

  // Where a TOML string may begin: after '=', '[', '{' or ',', first on a line, or after the '.'
  // of a dotted key. Elsewhere (0.'x' in a value) a quote is part of a malformed bare value.
  bool starts_token() const {
    return prev_ == '\n' || prev_ == '=' || prev_ == '[' || prev_ == '{' || prev_ == ',' ||
           (prev_ == '.' && expect_key_);
  }

  // toml++ 3.3 tests the character after a backslash, and after a line-ending backslash the
  // first one past the whitespace, with is_whitespace(), whose table reaches TOML_UNREACHABLE
  // for most code points in U+00A1..U+0499 and U+FC06..U+FEFE. None of them may stand there.
  void check_after_backslash(bool multi) {
    std::size_t i = pos_ + 1;
    if (i < text_.size() && static_cast<unsigned char>(text_[i]) >= 0x80)
      fail("non-ASCII character after a backslash in a string");
    if (!multi) return;
    while (i < text_.size() && (text_[i] == ' ' || text_[i] == '\t')) ++i;
    if (i < text_.size() && static_cast<unsigned char>(text_[i]) >= 0x80)
      fail("non-ASCII character after a line-ending backslash in a string");
    if (i >= text_.size() || (text_[i] != '\n' && text_[i] != '\r')) return;
    while (i < text_.size() &&
           (text_[i] == ' ' || text_[i] == '\t' || text_[i] == '\n' || text_[i] == '\r')) {
      if (text_[i] == '\n') ++line_;
      ++i;
    }
    if (i < text_.size() && static_cast<unsigned char>(text_[i]) >= 0x80)
      fail("non-ASCII character after a line-ending backslash in a string");
    pos_ = i;
  }

  // From an opening quote to past the closing one; basic strings know backslash escapes.
  void skip_string(char quote) {
    const bool multi = text_.substr(pos_, 3) == std::string(3, quote);
    pos_ += multi ? 3 : 1;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\\' && quote == '"') {
        const std::size_t before = pos_;
        check_after_backslash(multi);
        if (pos_ == before) {  // an ordinary escape: skip the backslash and the next byte
          if (pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') ++line_;
          pos_ += 2;
        }
      } else if (c == '\n') {
        if (!multi) return;  // unterminated: toml++ reports it
        ++line_;
        ++pos_;
      } else if (c == quote && !multi) {
        ++pos_;
        return;
      } else if (c == quote) {
        // A run of three or more closes; up to two more quotes before it belong to the string.
        std::size_t run = 0;
        while (pos_ + run < text_.size() && text_[pos_ + run] == quote) ++run;
        pos_ += run;
        if (run >= 3) return;
      } else {
        ++pos_;
      }
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::uint32_t line_ = 1;
  std::string open_;        // the open '[' (array), 'h' (table header) and '{', innermost last
  bool expect_key_ = true;  // a key may come next, not a value
  bool in_bare_ = false;    // inside a bare value
  std::size_t chain_ = 1;   // segments of the dotted key (or number) being read
  char prev_ = '\n';        // last character outside strings that is not a space or tab
};

}  // namespace

TomlError::TomlError(std::string_view source, std::uint32_t line, std::string_view problem)
    : IoError(std::filesystem::path(source), line, problem), line_(line), problem_(problem) {}

std::optional<TomlTextProblem> check_toml_text(std::string_view text) {
  return PreScan(text).run();
}

toml::table parse_toml(std::string_view text, std::string_view source) {
  if (text.size() > kMaxTomlBytes) {
    throw TomlError(source, 0,
                    "larger than " + std::to_string(kMaxTomlBytes) + " bytes: not a TOML file");
  }
  if (const auto problem = check_toml_text(text)) {
    throw TomlError(source, problem->line, problem->problem);
  }
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw TomlError(source, e.source().begin.line, e.description());
  }
}

std::string read_toml_file(const std::filesystem::path& path, std::size_t max_bytes) {
  try {
    return detail::load_file(path, max_bytes);
  } catch (const IoError& e) {
    // IoError's message already starts with the path.
    const std::string what = e.what();
    const std::string prefix = path.string() + ": ";
    throw TomlError(path.string(), 0, what.starts_with(prefix) ? what.substr(prefix.size()) : what);
  }
}

}  // namespace rangefit::io
