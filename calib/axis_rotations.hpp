#pragma once
// Rotations about one coordinate axis by an angle in radians (a joint turning about its axis).

#include <Eigen/Geometry>

namespace rangefit::calib {

inline Eigen::Matrix3d rot_x(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix();
}
inline Eigen::Matrix3d rot_y(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

}  // namespace rangefit::calib
