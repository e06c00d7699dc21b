#pragma once
// Scene files (TOML). Lengths in mm, angles in degrees (converted to rad on load). Example:
//
//   [[object]]
//   name = "table"
//   type = "plane"            # plane | box | cylinder | sphere | superquadric | mesh | bore_plate
//   size = [800.0, 600.0]     # plane: x, y; box: x, y, z
//   position = [0.0, 0.0, 0.0]  # mm, scene frame
//   rpy_deg = [0.0, 0.0, 0.0]   # R = Rz(yaw) Ry(pitch) Rx(roll); or z_axis = [x, y, z]
//
//   cylinder: radius, height          sphere: radius
//   superquadric: a = [a1, a2, a3], eps = [e1, e2], taper = [kx, ky]
//   mesh: file = "part.stl" (relative to the scene file)
//   bore_plate: cell, thickness, segments, and [[object.bore]] tables with name, kind
//     (straight | slanted | chamfered | rounded | notched), diameter, slant_deg, edge, notches,
//     notch_depth, notch_width_deg
//
//   [[bore]]           ground truth of a bore in a mesh: name, kind, diameter, opening = [x, y, z]
//                      (scene frame, on the surface), axis = [x, y, z] (into the material)
//   [sensors.css]      position/rpy_deg: pose of the CSS eq. 4.17 world frame in the scene
//   [sensors.stripe]   pose of the stripe cell's world frame
//   [sensors.pantilt]  pose of the pan-tilt head's world frame (eq. 5.7)
//
// Errors throw SceneError whose message names the file, the line and the field.

#include <stdexcept>
#include <string>

#include "sim/scene.hpp"

namespace rangefit::sim {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Scene load_scene(const std::string& path);
// Same from text; `name` stands for the file in messages, relative mesh paths resolve against
// base_dir.
Scene parse_scene(const std::string& text, const std::string& name, const std::string& base_dir);

}  // namespace rangefit::sim
