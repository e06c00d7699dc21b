#pragma once
// Text that came from outside (request ids, model and sensor names, file names) made safe for one
// log line: a newline with "[critical] FAKE LINE" after it or an ANSI escape sequence must show
// up as data, not as a forged line or a recoloured terminal, and a megabyte id must not become a
// megabyte line.

#include <cstddef>
#include <string>
#include <string_view>

namespace rangefit::daemon {

inline constexpr std::size_t kMaxLoggedBytes = 256;

// Printable ASCII is kept; a backslash becomes "\\", \n \r \t their C escapes, and every other
// byte (control characters, DEL, ESC, all bytes >= 0x80) "\xNN". Input beyond max_bytes is cut
// and "...(+N bytes)" appended. The result never contains a control character.
std::string log_escape(std::string_view text, std::size_t max_bytes = kMaxLoggedBytes);

}  // namespace rangefit::daemon
