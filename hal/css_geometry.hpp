#pragma once
// Geometry of the Circular Scanning Sensor on the robot's last joint (thesis 4.2.1, fig. 4.14 and
// 4.16, eq. 4.17-4.20). Shared by the simulator (which casts these rays) and fusion (which turns
// ranges back into points), so both sides use one model. All lengths mm, angles rad.
//
// Sensor frame "css": origin on the sensor axis at the nominal standoff below the body, z toward
// the sensor body, x the scan direction. The beam leaves the laser point p_LD on the body and
// passes through a point circling the origin in the xy-plane (the 27 mm scan circle); the return
// is seen from the CCD point p_CCD. range_mm is the distance from p_LD along the beam.
//
// World frame "world" (eq. 4.17): origin on the last joint axis, which is the world y-axis; at
// omega = 0 the sensor origin sits at (0, 0, R) and the beam looks roughly along -z, so a scanned
// surface lies near z = R and faces +z.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace rangefit::hal {

struct CssGeometry {
  double standoff_mm = 88.5;          // nominal standoff r: body to scan-circle plane
  double scan_diameter_mm = 27.0;     // d: diameter of the beam's circle at the standoff
  double laser_ccd_distance_mm = 27.0;  // p_LD and p_CCD, symmetric about the y-axis on x
  double phase_rad = 0.0;             // beam angle of sample 0 (index pulse offset)
  double min_range_mm = 65.0;         // working range along the beam
  double max_range_mm = 130.0;
  double eta_rad = 28.8 * std::numbers::pi / 180.0;  // eq. 4.18: sensor tilt about x_s
  double pivot_radius_mm = 285.8;     // eq. 4.20: R, last joint axis to sensor origin

  Eigen::Vector3d laser_point() const { return {-0.5 * laser_ccd_distance_mm, 0.0, standoff_mm}; }
  Eigen::Vector3d ccd_point() const { return {0.5 * laser_ccd_distance_mm, 0.0, standoff_mm}; }

  // Beam angle of sample i of a revolution with n samples.
  double beam_angle(int i, int n) const { return phase_rad + 2.0 * std::numbers::pi * i / n; }

  // Unit beam direction in the sensor frame for a beam angle.
  Eigen::Vector3d beam_direction(double angle) const {
    const double rc = 0.5 * scan_diameter_mm;
    const Eigen::Vector3d on_circle(rc * std::cos(angle), rc * std::sin(angle), 0.0);
    return (on_circle - laser_point()).normalized();
  }

  // Sensor-frame point of a range sample.
  Eigen::Vector3d sensor_point(double angle, double range_mm) const {
    return laser_point() + range_mm * beam_direction(angle);
  }

  // Eq. 4.17: x_w = R_y(omega) * (R_x(eta) * x_s + t), t = (0, 0, R). omega is the path angle of
  // the last joint (0 at the scan centre).
  Eigen::Isometry3d T_world_css(double omega_rad) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(omega_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
    Eigen::Isometry3d S = Eigen::Isometry3d::Identity();
    S.linear() = Eigen::AngleAxisd(eta_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
    S.translation() = Eigen::Vector3d(0.0, 0.0, pivot_radius_mm);
    return T * S;
  }
};

}  // namespace rangefit::hal
