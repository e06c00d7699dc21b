#pragma once
// Checks a decoded request against the running configuration before it is queued: resolves the
// default sensor for its kind, converts sweep units (metres on the wire, mm inside, for linear
// sensors) and rejects what cannot be scanned. Every rejection is answered with an error result
// naming the problem; nothing reaches the pipeline that the pipeline would have to guess about.

#include <cstddef>
#include <string>
#include <string_view>

#include "daemon/service/config.hpp"
#include "daemon/service/scan_types.hpp"

namespace rangefit::daemon {

inline constexpr std::size_t kMaxRequestIdLength = 256;
inline constexpr std::size_t kMaxNameLength = 128;  // model and sensor names
inline constexpr std::size_t kMaxViews = 4;         // scans a learn request fuses (sensors)
inline constexpr std::size_t kMaxCalibrationScans = 31;  // earlier poses a css calibration joins

// Empty when text is 1..max_length bytes of printable ASCII (0x20..0x7e), else the reason, naming
// `what` but never echoing the text (it may be megabytes of escape sequences).
std::string check_name(std::string_view text, std::string_view what, std::size_t max_length);

// Returns an empty string when the request is valid (and completes it in place), else the reason.
// The id, model and sensor are checked with check_name first, so a reason never carries hostile
// text; the caller must still log the id through log_escape (daemon/log_escape.hpp), since a
// rejected request's id is by definition not valid.
std::string validate_request(ScanRequest& request, const DaemonConfig& config);

}  // namespace rangefit::daemon
