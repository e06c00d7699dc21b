#pragma once
// A cone's or elliptic bore's fitted shape as JSON, one form for `rangefit bore --json` and the
// service's result details: half_angle (rad) and cylinder_radius (mm) of a cone; radius2 (mm)
// and major_axis of an ellipse; their standard errors under "sigma", each key with its unit
// (radius_mm, entrance_mm, axis_rad, half_angle_rad, cylinder_radius_mm, radius2_mm,
// major_axis_rad); the inliers' rms (mm); and read back for a picture of the result.

#include <nlohmann/json.hpp>
#include <optional>

#include "detect/bore/bore_result.hpp"

namespace rangefit::daemon {

nlohmann::json bore_shape_json(const BoreShape& s);

// The shape back from that JSON (a result read back to draw it): empty without "model" or for
// "cylinder"; throws std::invalid_argument for another model than cone or ellipse or values no
// fit gives
// (half-angle outside (0, 80 deg), a cylinder radius below 0, radius2 <= 0, a zero or non-finite
// major axis).
std::optional<BoreShape> bore_shape_from_json(const nlohmann::json& j);

}  // namespace rangefit::daemon
