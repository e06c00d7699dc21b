#pragma once
// One exit-code contract for every way a result reaches a user: found, not found (a detector
// ran and said no, with one of its own reasons), or an error (bad request, device fault, busy,
// timeout, bad prior or model). The service sends only the reason text over DDS, so the client
// tells "not found" from "error" by matching the detectors' own reason strings (detect/).

#include <string_view>

#include "daemon/service/scan_types.hpp"

namespace rangefit::daemon {

enum class Outcome { kFound, kNotFound, kError };

// True when reason is one a detector gives for a scene without the part (not for bad input).
bool is_not_found_reason(std::string_view reason);

Outcome outcome_of(const DetectionResult& result);

// 0 found, 2 not found, 1 error (daemon/cli/commands.hpp).
int exit_code_of(const DetectionResult& result);

}  // namespace rangefit::daemon
