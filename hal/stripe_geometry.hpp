#pragma once
// Geometry of the laser-stripe ranger (IVP MAPP2500 + LASIRIS line laser, thesis 5.2.1) and of
// the sensor cell that carries objects through its laser plane on a linear axis (fig. 5.8).
// Shared by the simulator (which casts the fan's rays) and fusion (which turns profiles back
// into points), so both sides use one model. All lengths mm, angles rad.
//
// Ranger frame "ranger": origin at the apex of the laser fan, z along the fan's centre line
// (away from the laser), x along the laser line, y the normal of the laser plane, so the laser
// plane is y = 0. A profile point (x_mm[k], z_mm[k]) of hal::RangerProfile is the ranger point
// (x, 0, z). Profile point k of n lies on the fan ray at theta_k = -fan/2 + fan * k / (n - 1),
// measured from +z toward +x. The camera that triangulates the stripe sits at camera_point(),
// out of the laser plane; a hit is seen only when the segment camera -> hit is unobstructed.
//
// Cell frame "cell": fixed to the cell base, z up, y the linear axis's direction of travel,
// origin on the table surface below the fan apex when the axis stands at position 0.
// Table frame "table" (the frame of the fused cloud, frame_id "world"): attached to the moving
// measurement table, equal to "cell" at axis position 0. A point fixed on the table at table
// coordinates p sits at cell coordinates p + s * axis_direction when the axis is at s.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace rangefit::hal {

// The ranger itself: where its fan rays go and what it can see. Defaults are the mobile head's
// MAPP2500 setup (thesis 5.2.1, fig. 5.15): 512 points per profile, baseline B = 425 mm, camera
// angle 60 deg, depth range A1 = 344 mm to A2 = 2685 mm. The fan angle of 30 deg is the
// simulator's (fig. 5.12).
struct StripeRanger {
  int points_per_profile = 512;
  double fan_angle_rad = 30.0 * std::numbers::pi / 180.0;  // full opening of the laser fan
  double min_depth_mm = 344.0;   // A1: smallest z a point may have (camera field of view)
  double max_depth_mm = 2685.0;  // A2: largest z
  double baseline_mm = 425.0;    // B: camera offset from the laser plane, along +y
  double camera_angle_rad = 60.0 * std::numbers::pi / 180.0;  // alpha: camera axis vs baseline

  // Angle from +z toward +x of profile point k of n (n >= 2).
  double ray_angle(int k, int n) const {
    return -0.5 * fan_angle_rad + fan_angle_rad * static_cast<double>(k) / (n - 1);
  }
  // Unit direction of fan ray k of n in the ranger frame; the ray starts at the origin.
  Eigen::Vector3d ray_direction(int k, int n) const {
    const double a = ray_angle(k, n);
    return {std::sin(a), 0.0, std::cos(a)};
  }
  // Centre of the camera's projection, ranger frame (for the simulator's occlusion test).
  Eigen::Vector3d camera_point() const { return {0.0, baseline_mm, 0.0}; }
  // Ranger-frame point of a profile sample.
  static Eigen::Vector3d ranger_point(double x_mm, double z_mm) { return {x_mm, 0.0, z_mm}; }
  bool depth_in_range(double z_mm) const { return z_mm >= min_depth_mm && z_mm <= max_depth_mm; }
};

// The sensor cell (fig. 5.8): the ranger looks down onto a measurement table that a FESTO linear
// axis moves along cell y. Thesis values: workspace 400 x 300 x 300 mm (length along the axis,
// width, height), table speed up to 6.3 mm/s, axis resolution 0.05 mm. The ranger pose is not
// given in the thesis: the default puts the fan apex 600 mm above the table (a 30 deg fan then
// covers ~320 mm, the workspace width) with the laser plane at cell y = 200 mm, so travelling
// the axis from 0 to 400 mm sweeps table y from +200 to -200 mm. Calibration (thesis ref. [48])
// replaces it through the configuration.
struct StripeCellGeometry {
  StripeRanger ranger{.points_per_profile = 512,
                      .fan_angle_rad = 30.0 * std::numbers::pi / 180.0,
                      .min_depth_mm = 250.0,  // 300 mm workspace height + margin
                      .max_depth_mm = 650.0,  // table surface at 600 mm + margin
                      .baseline_mm = 300.0,
                      .camera_angle_rad = 60.0 * std::numbers::pi / 180.0};
  // Pose of the ranger in the cell: apex at (0, 200, 600), looking down (z_ranger = -z_cell),
  // laser line along cell x (x_ranger = x_cell), hence y_ranger = -y_cell.
  Eigen::Vector3d ranger_position_cell_mm{0.0, 200.0, 600.0};
  Eigen::Vector3d ranger_rpy_cell_rad{std::numbers::pi, 0.0,
                                      0.0};            // roll, pitch, yaw (x-y-z fixed axes)
  Eigen::Vector3d axis_direction_cell{0.0, 1.0, 0.0};  // unit; table motion for increasing s
  double axis_travel_mm = 400.0;                       // usable travel from the reference point
  double max_speed_mm_s = 6.3;                         // thesis: maximum table speed

  Eigen::Isometry3d T_cell_ranger() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(ranger_rpy_cell_rad.z(), Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(ranger_rpy_cell_rad.y(), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(ranger_rpy_cell_rad.x(), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = ranger_position_cell_mm;
    return T;
  }

  // Table (world) frame from the ranger frame with the axis at position s (mm):
  // p_table = T_cell_ranger * p_ranger - s * axis_direction.
  Eigen::Isometry3d T_world_ranger(double axis_position_mm) const {
    Eigen::Isometry3d T = T_cell_ranger();
    T.translation() -= axis_position_mm * axis_direction_cell.normalized();
    return T;
  }
};

}  // namespace rangefit::hal
