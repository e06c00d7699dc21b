#pragma once
// Checks a decoded request against the running configuration before it is queued: resolves the
// default sensor for its kind, converts sweep units (metres on the wire, mm inside, for linear
// sensors) and rejects what cannot be scanned. Every rejection is answered with an error result
// naming the problem; nothing reaches the pipeline that the pipeline would have to guess about.

#include <string>

#include "daemon/config.hpp"
#include "daemon/scan_types.hpp"

namespace rangefit::daemon {

// Returns an empty string when the request is valid (and completes it in place), else the reason.
std::string validate_request(ScanRequest& request, const DaemonConfig& config);

}  // namespace rangefit::daemon
