#pragma once
// Which way the sensor that took a scan looked at a point of it, from the SensorView the scan
// carries (detect/sensor_view.hpp; set by the cell's scan loop, kept in rangefit's PLY and PCD
// files): the picture's first panel looks from there, so it shows the scene as the sensor saw it.

#include <Eigen/Core>
#include <optional>

#include "detect/common/sensor_view.hpp"

namespace rangefit::render {

// Unit direction from `target` toward the sensor. A single eye: toward it. A laser-stripe ranger
// (linear or rotary sweep): halfway between the laser apex and the camera of the profile whose
// laser plane holds `target` (both had to see a point for it to be measured), or of the middle
// of the sweep when no profile does. nullopt when the view is unknown or invalid.
std::optional<Eigen::Vector3d> toward_scan_sensor(const SensorView& view,
                                                  const Eigen::Vector3d& target);

}  // namespace rangefit::render
