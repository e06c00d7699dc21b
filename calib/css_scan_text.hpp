#pragma once
// The CSS sphere scans the hand-eye calibration reads (calib/css_calibration.hpp), as text (what
// `rangefit calibrate css --scans` takes): per robot pose the last joint's frame as the robot
// controller reports it, then the raw range samples taken there. One item per line, '#' starts
// a comment:
//
//   rangefit-css-sphere-scans 1
//   pose 412.5 -150 396.25 0.1 -0.2 1.57   # T_base_joint: X Y Z mm, ROLL PITCH YAW rad
//   -0.0873 1.5708 97.125                  # reported joint angle, beam angle (rad), range (mm)
//
// with R = Rz(yaw) Ry(pitch) Rx(roll) (hal's convention). Parsing and formatting are pure.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calib/css_calibration.hpp"

namespace rangefit::calib {

struct CssScansParse {
  std::optional<std::vector<CssSphereScan>> scans;
  std::string error;  // "<source>:<line>: <problem>" when not
};

CssScansParse parse_css_scans(std::string_view text, std::string_view source = "scans");
std::string format_css_scans(const std::vector<CssSphereScan>& scans);

// The pose of a line 'pose X Y Z ROLL PITCH YAW' and back.
Eigen::Isometry3d pose_from_xyz_rpy(const double v[6]);
void xyz_rpy_of(const Eigen::Isometry3d& T, double v[6]);

}  // namespace rangefit::calib
