#pragma once
// What the sensor that took a scan knows about where its rays came from, in the frame of the
// scan's points: a direction or position to orient normals toward (bores) and the visibility
// model of the sweep (objects: coverage and free-space checks). Built from the same geometry
// the drivers, the simulator and fusion use, for the sweep that was actually run.

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "detect/common/sensor_view.hpp"
#include "hal/css_geometry.hpp"
#include "hal/pan_tilt_geometry.hpp"
#include "hal/stripe_geometry.hpp"

namespace rangefit::daemon {

struct ScanSensor {
  std::optional<Eigen::Vector3d> view_dir;         // unit, from the scene toward the sensor
  std::optional<Eigen::Vector3d> sensor_position;  // mm; preferred over view_dir when set
  SensorView view;                                 // kUnknown: nothing known
  // The frame fusion built the scan in, seen from the scan's frame (p_scan = T p_fusion), and
  // the stripe cell's geometry fusion used: what a calibration needs to take the fused points
  // back to the ranger's raw profiles (daemon/service/calibrate_request.hpp).
  Eigen::Isometry3d T_scan_fusion = Eigen::Isometry3d::Identity();
  std::optional<hal::StripeCellGeometry> stripe;
  std::string stripe_camera;  // its name in [[fusion.stripe_cell.cameras]]; empty: the first
  // The CSS geometry and joint zero fusion used (omega = reported angle - zero): what takes a
  // fused CSS point back to the joint angle, beam angle and range it was made of.
  struct CssFusion {
    hal::CssGeometry geometry;
    double omega_zero_rad = 0.0;
  };
  std::optional<CssFusion> css;
  // The pan-tilt head's geometry fusion used, and per grid row of the scan the pan and tilt
  // (rad, as the head reported them) fusion placed that profile with: what takes the fused
  // points back to the ranger's raw profiles.
  std::optional<hal::PanTiltGeometry> pan_tilt;
  std::vector<std::array<double, 2>> row_poses;
};

// The CSS in fusion's CSS world frame (eq. 4.17): it looks along the sensor's -z at the scan
// centre (omega = 0), so the direction toward it is the sensor's +z there.
ScanSensor css_sensor(const hal::CssGeometry& g, double omega_zero_rad);

// The stripe cell in the table frame (the fused cloud's): the fan apex moves relative to the
// table by -s * axis_direction while the axis runs from `from` to `to` (mm).
// camera: as ScanSensor::stripe_camera.
ScanSensor stripe_sensor(const hal::StripeCellGeometry& g, double from_mm, double to_mm,
                         std::string camera = {});

// The pan-tilt head in its world frame (eq. 5.7): the laser plane turns about world x through
// the pan-tilt centre by pan - pan_zero in [-half, +half], at the fixed tilt the unit reports.
ScanSensor pan_tilt_sensor(const hal::PanTiltGeometry& g, double half_sweep_rad,
                           double reported_tilt_rad);

// The same sensor seen from another frame: p' = T p for points, R v for directions.
ScanSensor transformed(const ScanSensor& s, const Eigen::Isometry3d& T);

}  // namespace rangefit::daemon
