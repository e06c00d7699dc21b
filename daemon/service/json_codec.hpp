#pragma once
// JSON forms of requests and results: the spool's request.json/result.json and what the CLI
// prints. Units as internally: mm and rad; poses as translation_mm + quaternion_wxyz.

#include <nlohmann/json.hpp>
#include <string>

#include "daemon/service/scan_types.hpp"

namespace rangefit::daemon {

nlohmann::json to_json(const ScanRequest& r);
nlohmann::json to_json(const DetectionResult& r);
// Both return false and set *error on missing or mistyped fields; they never throw.
bool from_json(const nlohmann::json& j, ScanRequest& out, std::string* error);
bool from_json(const nlohmann::json& j, DetectionResult& out, std::string* error);

}  // namespace rangefit::daemon
