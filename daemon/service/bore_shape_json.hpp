#pragma once
// A cone's or elliptic bore's fitted shape as JSON, one form for `rangefit bore --json` and the
// service's result details: half_angle (rad) and cylinder_radius (mm) of a cone; radius2 (mm)
// and major_axis of an ellipse; their standard errors under "sigma"; the inliers' rms (mm).

#include <nlohmann/json.hpp>

#include "detect/bore_result.hpp"

namespace rangefit::daemon {

nlohmann::json bore_shape_json(const BoreShape& s);

}  // namespace rangefit::daemon
