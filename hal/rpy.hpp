#pragma once
// The one roll-pitch-yaw convention of rangefit: R = Rz(yaw) * Ry(pitch) * Rx(roll), fixed axes
// (the URDF / REP 103 convention). Scenes, device extrinsics in the daemon config, JSON and CLI
// poses and the calibration texts all read and write it, so a pose typed in one place means the
// same in every other. Lengths mm, angles rad.

#include <Eigen/Geometry>

namespace rangefit::hal {

inline Eigen::Matrix3d rpy_matrix(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// rpy = (roll, pitch, yaw), rad.
inline Eigen::Matrix3d rpy_matrix(const Eigen::Vector3d& rpy) {
  return rpy_matrix(rpy.x(), rpy.y(), rpy.z());
}

inline Eigen::Isometry3d pose_xyz_rpy(double x, double y, double z, double roll, double pitch,
                                      double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rpy_matrix(roll, pitch, yaw);
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

}  // namespace rangefit::hal
