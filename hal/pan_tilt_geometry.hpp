#pragma once
// Geometry of the mobile scanning head (thesis 5.2.1, fig. 5.14-5.16, eq. 5.7-5.10): a stripe
// ranger (hal/stripe_geometry.hpp) on an AMTEC pan-tilt unit that sweeps the laser plane across
// the scene. Shared by the simulator and fusion. All lengths mm, angles rad.
//
// Sensor frame "ranger": as in hal/stripe_geometry.hpp (laser plane y = 0, z along the fan).
// World frame "world" (eq. 5.7): at pan = tilt = 0 its axes are parallel to the ranger's;
// x_w = R_x(pan) * R_y(tilt) * (x_s + t_s) + t_w. Pan turns about world x, which lies in the laser
// plane, so panning sweeps the plane across the scene; tilt turns about the sensor's y (the
// plane normal) before it. t_s is the sensor origin relative to the pan-tilt centre (sensor
// axes), t_w the pan-tilt centre in the world.

#include <Eigen/Geometry>
#include <numbers>

#include "hal/stripe_geometry.hpp"

namespace rangefit::hal {

struct PanTiltGeometry {
  // MAPP2500 on the head: B = 425 mm, alpha = 60 deg, A1 = 344 mm .. A2 = 2685 mm, 512 points.
  StripeRanger ranger{};
  // Eq. 5.10. Not given in the thesis; identity placement until calibrated (ref. [48]).
  Eigen::Vector3d t_s_mm{0.0, 0.0, 0.0};
  Eigen::Vector3d t_w_mm{0.0, 0.0, 0.0};
  // Zero offsets of the unit's encoders: pan = reported pan - pan_zero (same for tilt).
  double pan_zero_rad = 0.0;
  double tilt_zero_rad = 0.0;
  // Thesis scan (fig. 5.17): 50 deg sweep at 10 deg/s, integration 17 ms, <= 100 profiles/s.
  double sweep_angle_rad = 50.0 * std::numbers::pi / 180.0;
  double sweep_rate_rad_s = 10.0 * std::numbers::pi / 180.0;
  double profile_rate_hz = 100.0;

  // Eq. 5.7 as a transform: world from ranger, for the reported pan and tilt angles.
  Eigen::Isometry3d T_world_ranger(double pan_rad, double tilt_rad) const {
    const Eigen::Matrix3d R =
        (Eigen::AngleAxisd(pan_rad - pan_zero_rad, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(tilt_rad - tilt_zero_rad, Eigen::Vector3d::UnitY()))
            .toRotationMatrix();  // eq. 5.8 * eq. 5.9
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    T.translation() = R * t_s_mm + t_w_mm;
    return T;
  }
};

}  // namespace rangefit::hal
