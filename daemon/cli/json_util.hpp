#pragma once
// Small JSON helpers shared by the CLI subcommands.

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace rangefit::cli {

// [x, y, z]
inline nlohmann::json json_vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace rangefit::cli
