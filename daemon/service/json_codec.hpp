#pragma once
// JSON forms of requests and results: the spool's request.json/result.json and what the CLI
// prints. Units as internally: mm and rad; poses as translation_mm + quaternion_wxyz.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <string>

#include "daemon/service/scan_types.hpp"

namespace rangefit::daemon {

// A vector as the JSON array [x, y, z].
inline nlohmann::json json_vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// A part's pose as a result writes it: "center" and "z_axis" in the world frame (mm) and the
// rotation as "quaternion" [w, x, y, z].
inline nlohmann::json pose_json(const Eigen::Isometry3d& T_world_part) {
  const Eigen::Quaterniond q(T_world_part.linear());
  return {{"center", json_vec(T_world_part.translation())},
          {"z_axis", json_vec(T_world_part.linear().col(2))},
          {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

nlohmann::json to_json(const ScanRequest& r);
nlohmann::json to_json(const DetectionResult& r);
// Both return false and set *error on missing or mistyped fields; they never throw.
bool from_json(const nlohmann::json& j, ScanRequest& out, std::string* error);
bool from_json(const nlohmann::json& j, DetectionResult& out, std::string* error);

}  // namespace rangefit::daemon
