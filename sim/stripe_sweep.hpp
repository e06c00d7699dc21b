#pragma once
// Where the laser fan and the camera of a laser-stripe ranger are at each profile of a sweep, in
// the table frame (z up, table surface z = 0, mm and rad): the stripe cell, whose table carries
// the scene through a fixed laser plane (hal/stripe_geometry.hpp; in the table frame the ranger
// moves along +y), and the pan-tilt head, which turns the ranger about a horizontal axis
// (hal/pan_tilt_geometry.hpp). The camera sits beside the laser plane at the triangulation angle
// and moves with the apex, so a point needs two clear lines of sight (detect/sensor_view.hpp).
// sim/stripe_scan.hpp casts the rays; view() tells the detector exactly this geometry.

#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "detect/common/sensor_view.hpp"

namespace rangefit::sim {

// How a scan is taken: the factors a varied scene draws (sim/varied_scene.hpp).
struct ScanSetup {
  bool pan_tilt = false;            // false: stripe cell (linear sweep); true: pan-tilt head
  double triangulation_deg = 45.0;  // camera ray vs laser ray at the scene centre
  int camera_side = +1;             // side of the laser plane the camera is on (+1: +y, -1: -y)
  bool two_cameras = false;  // and a second camera on the other side at the same angle, either
                             // seeing a point enough to measure it
  double laser_height_mm = 600.0;   // fan apex above the table at sweep 0
  // The fan's centre ray at sweep 0, off vertical toward +y (cell: a tilted laser plane; pan-tilt:
  // the head looks at the scene from -y at this angle).
  double laser_tilt_deg = 0.0;
  double step_mm = 0.7;        // profile spacing on the table (pan-tilt: at the scene centre)
  int points_per_profile = 0;  // fan rays per profile; 0: as many as max_points allows
  double max_points = 150000;  // cap on profiles x rays (the rays per profile give way)
  double noise_mm = 0.1;       // sigma of the range along the laser ray
  double outlier_share = 0.0;  // share of points moved to a wrong range on their laser ray
};

// One profile's rays: fan ray k of n leaves `apex` at angle -fan/2 + fan k / (n - 1) from
// `centre` toward `line`; the camera's projection centre is `camera` (and a second camera's,
// if the ranger has one, `second_camera`).
struct ProfilePose {
  Eigen::Vector3d apex, centre, line, normal, camera;
  std::optional<Eigen::Vector3d> second_camera;
  Eigen::Vector3d ray(double angle) const {
    return std::cos(angle) * centre + std::sin(angle) * line;
  }
};

struct StripeSweep {
  SensorView::Kind kind = SensorView::Kind::kLinearSweep;  // kLinearSweep or kRotarySweep
  // At sweep position 0: the fan apex, its unit centre ray and laser line direction (the plane
  // normal is line x centre), and the camera relative to the apex.
  Eigen::Vector3d apex0{0.0, 0.0, 600.0};
  Eigen::Vector3d centre0{0.0, 0.0, -1.0};
  Eigen::Vector3d line0{1.0, 0.0, 0.0};
  Eigen::Vector3d camera_offset0{0.0, 600.0, 0.0};
  Eigen::Vector3d second_camera_offset0 = Eigen::Vector3d::Zero();  // zero: one camera
  // Linear: unit motion of the apex per mm of sweep. Rotary: unit axis of the turn through pivot.
  Eigen::Vector3d direction{0.0, 1.0, 0.0};
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  double sweep_start = 0.0;  // profile j is at sweep_start + j * sweep_step (mm or rad)
  double sweep_step = 1.0;
  int profiles = 0;
  double fan_rad = 0.5;
  int rays = 512;  // fan rays per profile

  double position(int profile) const { return sweep_start + profile * sweep_step; }
  double ray_angle(int k) const { return -0.5 * fan_rad + fan_rad * k / (rays - 1); }
  ProfilePose pose(double s) const;
  // The sweep position whose laser plane holds p (the nearest to 0 for a turn); NaN if none.
  double position_of(const Eigen::Vector3d& p) const;
  // Exactly this geometry for the detector (the scan's sweep range, padded by 1e-9 of a step).
  SensorView view() const;
};

// The sweep of `setup` over `cover` (table frame): the fan wide enough for every point of the
// box at every profile and the sweep just across it, profiles x rays <= setup.max_points.
StripeSweep make_sweep(const ScanSetup& setup, const Eigen::AlignedBox3d& cover);

// Fan rays per profile for `profiles` profiles: setup.points_per_profile (0: 2048), fewer when
// the product would pass setup.max_points, at least 16.
int rays_for(const ScanSetup& setup, int profiles);

}  // namespace rangefit::sim
