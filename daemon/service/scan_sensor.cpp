#include "daemon/service/scan_sensor.hpp"

#include <algorithm>

namespace rangefit::daemon {

ScanSensor css_sensor(const hal::CssGeometry& g, double omega_zero_rad) {
  ScanSensor s;
  s.view_dir = g.T_world_css(0.0).linear() * Eigen::Vector3d::UnitZ();
  s.css = ScanSensor::CssFusion{g, omega_zero_rad};
  return s;
}

ScanSensor stripe_sensor(const hal::StripeCellGeometry& g, double from_mm, double to_mm,
                         std::string camera) {
  const Eigen::Isometry3d T0 = g.T_world_ranger(0.0);
  ScanSensor s;
  SensorView& v = s.view;
  v.kind = SensorView::Kind::kLinearSweep;
  v.origin = T0.translation();
  v.plane_normal = T0.linear().col(1);  // the laser plane is the ranger's y = 0
  v.camera_offset = T0.linear() * g.ranger.camera_point();
  v.direction = -g.axis_direction_cell.normalized();  // the table moves by +s, the ranger by -s
  v.sweep_min = std::min(from_mm, to_mm);
  v.sweep_max = std::max(from_mm, to_mm);
  s.stripe = g;
  s.stripe_camera = std::move(camera);
  return s;
}

ScanSensor pan_tilt_sensor(const hal::PanTiltGeometry& g, double half_sweep_rad,
                           double reported_tilt_rad) {
  const Eigen::Isometry3d T0 = g.T_world_ranger(g.pan_zero_rad, reported_tilt_rad);
  ScanSensor s;
  SensorView& v = s.view;
  v.kind = SensorView::Kind::kRotarySweep;
  v.origin = T0.translation();
  v.plane_normal = T0.linear().col(1);
  v.camera_offset = T0.linear() * g.ranger.camera_point();
  v.direction = Eigen::Vector3d::UnitX();  // pan, eq. 5.8
  v.pivot = g.t_w_mm;
  v.sweep_min = -half_sweep_rad;
  v.sweep_max = half_sweep_rad;
  s.pan_tilt = g;
  return s;
}

ScanSensor transformed(const ScanSensor& s, const Eigen::Isometry3d& T) {
  ScanSensor out = s;
  const Eigen::Matrix3d R = T.linear();
  if (s.view_dir) out.view_dir = R * *s.view_dir;
  if (s.sensor_position) out.sensor_position = T * *s.sensor_position;
  SensorView& v = out.view;
  v.origin = T * s.view.origin;
  v.plane_normal = R * s.view.plane_normal;
  v.camera_offset = R * s.view.camera_offset;
  v.second_camera_offset = R * s.view.second_camera_offset;
  v.direction = R * s.view.direction;
  v.pivot = T * s.view.pivot;
  out.T_scan_fusion = T * s.T_scan_fusion;
  return out;
}

}  // namespace rangefit::daemon
