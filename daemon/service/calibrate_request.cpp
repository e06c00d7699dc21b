#include "daemon/service/calibrate_request.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "daemon/service/json_codec.hpp"
#include "detect/common/angles.hpp"

namespace rangefit::daemon {
std::string toml_vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(10);
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

PointCloud in_fusion_frame(const PointCloud& cloud, const ScanSensor& sensor) {
  PointCloud out = cloud;
  const Eigen::Isometry3d T_fusion_scan = sensor.T_scan_fusion.inverse();
  for (auto& p : out.points) p = T_fusion_scan * p;
  return out;
}

RawStripeProfiles raw_stripe_profiles(const PointCloud& cloud, const hal::StripeCellGeometry& g) {
  RawStripeProfiles out;
  if (cloud.grid.empty() ||
      cloud.grid.index.size() != static_cast<std::size_t>(cloud.grid.rows) * cloud.grid.cols) {
    out.error = "the scan is not organised in profiles (a stripe sweep is)";
    return out;
  }
  const Eigen::Isometry3d T = g.T_cell_ranger();
  const Eigen::Isometry3d T_inv = T.inverse();
  const Eigen::Vector3d d = g.axis_direction_cell.normalized();
  const Eigen::Vector3d n = T.linear().col(1);  // the laser plane is the ranger's y = 0
  const double nd = n.dot(d);
  if (!(std::abs(nd) > 1e-6)) {
    out.error = "the configured axis lies in the laser plane";
    return out;
  }
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (int r = 0; r < cloud.grid.rows; ++r) {
    hal::RangerProfile p;
    p.sequence = static_cast<std::uint32_t>(r);
    p.x_mm.assign(static_cast<std::size_t>(cloud.grid.cols), kNaN);
    p.z_mm.assign(static_cast<std::size_t>(cloud.grid.cols), kNaN);
    double s_sum = 0.0;
    int count = 0;
    for (int c = 0; c < cloud.grid.cols; ++c) {
      const std::int32_t i = cloud.grid.at(r, c);
      if (i < 0 || static_cast<std::size_t>(i) >= cloud.points.size()) continue;
      const Eigen::Vector3d& X = cloud.points[static_cast<std::size_t>(i)];
      const double s = n.dot(T.translation() - X) / nd;
      const Eigen::Vector3d q = T_inv * (X + s * d);
      p.x_mm[static_cast<std::size_t>(c)] = static_cast<float>(q.x());
      p.z_mm[static_cast<std::size_t>(c)] = static_cast<float>(q.z());
      s_sum += s;
      ++count;
    }
    if (count == 0) continue;  // a profile without returns says nothing
    out.axis_mm.push_back(s_sum / count);
    out.profiles.push_back(std::move(p));
  }
  if (out.profiles.empty()) out.error = "the scan has no points";
  return out;
}

std::string stripe_calibration_toml(const calib::StripeCalibrationResult& r,
                                    const std::string& source) {
  const hal::StripeCellGeometry& g = r.geometry;
  std::ostringstream toml;
  toml << "# rangefit stripe cell calibration, from " << source
       << "; see the .report.txt beside it. Not applied: include it in the configuration.\n"
       << "[fusion.stripe_cell]\n"
       << "ranger_position_cell_mm = " << toml_vec(g.ranger_position_cell_mm) << "\n"
       << "ranger_rpy_cell_rad = " << toml_vec(g.ranger_rpy_cell_rad) << "\n"
       << "axis_direction_cell = " << toml_vec(g.axis_direction_cell) << "\n";
  return toml.str();
}

std::string stripe_calibration_report(const calib::StripeCalibrationResult& r,
                                      const hal::StripeCellGeometry& start,
                                      const std::string& source) {
  const hal::StripeCellGeometry& g = r.geometry;
  std::ostringstream rep;
  rep.precision(4);
  rep << "stripe cell calibration (thesis 3.2), " << source << "\n";
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    rep << "  linear round " << i + 1 << ": corner rms " << r.rounds[i].corner_rms_mm
        << " mm, plane points";
    for (const auto n : r.rounds[i].plane_points) rep << " " << n;
    rep << "\n";
  }
  rep << "  refinement: " << r.points << " plane points, rms " << r.initial_rms_mm << " -> "
      << r.rms_mm << " mm in " << r.lm_iterations << " iterations\n"
      << "  ranger position " << toml_vec(g.ranger_position_cell_mm) << " mm (was "
      << toml_vec(start.ranger_position_cell_mm) << "), 1 sigma " << toml_vec(r.position_sigma_mm)
      << " mm\n"
      << "  ranger rpy " << toml_vec(g.ranger_rpy_cell_rad) << " rad (was "
      << toml_vec(start.ranger_rpy_cell_rad) << "), 1 sigma about its axes "
      << toml_vec(r.rotation_sigma_rad / kDeg) << " deg\n"
      << "  axis direction " << toml_vec(g.axis_direction_cell) << " (was "
      << toml_vec(start.axis_direction_cell) << "), 1 sigma " << r.axis_sigma_rad.x() / kDeg << ", "
      << r.axis_sigma_rad.y() / kDeg << " deg\n";
  return rep.str();
}

DetectionResult calibrate_request(const PointCloud& cloud, const ScanRequest& request,
                                  const ScanSensor& sensor, std::uint64_t default_seed) {
  // Validation admits only the stripe target (and only on a stripe sensor).
  if (!sensor.stripe) {
    return DetectionResult::error(request,
                                  "calibrate stripe: the scan's sensor reports no stripe cell "
                                  "geometry (a stripe sweep on the cell is needed, not a replay)");
  }
  const RawStripeProfiles raw = raw_stripe_profiles(in_fusion_frame(cloud, sensor), *sensor.stripe);
  if (!raw.error.empty()) return DetectionResult::error(request, "calibrate stripe: " + raw.error);
  calib::StripeCalibrationInput in;
  in.profiles = raw.profiles;
  in.axis_mm = raw.axis_mm;
  in.cube = {request.target.edge_mm, request.target.bar_mm};
  in.T_table_cube = request.target.T_table_target;
  calib::StripeCalibrationOptions options;
  options.planes.seed = request.seed != 0 ? request.seed : default_seed;
  const calib::StripeCalibrationResult r =
      calib::calibrate_stripe_cell(in, *sensor.stripe, options);
  DetectionResult out;
  const hal::StripeCellGeometry& g = r.geometry;
  out.details = {
      {"target", request.target.kind}, {"applied", false}, {"profiles", raw.profiles.size()}};
  if (!r.ok) {
    out.reason = std::string(kNotCalibrated) + r.reason;
    return out;
  }
  out.found = true;
  out.details["rms_mm"] = r.rms_mm;
  out.details["initial_rms_mm"] = r.initial_rms_mm;
  out.details["plane_points"] = r.points;
  out.details["fusion.stripe_cell"] = {
      {"ranger_position_cell_mm", json_vec(g.ranger_position_cell_mm)},
      {"ranger_rpy_cell_rad", json_vec(g.ranger_rpy_cell_rad)},
      {"axis_direction_cell", json_vec(g.axis_direction_cell)}};
  out.details["sigma"] = {{"position_mm", json_vec(r.position_sigma_mm)},
                          {"rotation_rad", json_vec(r.rotation_sigma_rad)},
                          {"axis_rad", {r.axis_sigma_rad.x(), r.axis_sigma_rad.y()}}};
  // The ranger's pose in the cell as a part, so the result can be drawn and published.
  out.parts.push_back({"ranger", g.T_cell_ranger(), 1.0, 0});
  const std::string source = "rangefitd request " + request.id + " on " + request.sensor;
  out.files.emplace_back("calibration_stripe.toml", stripe_calibration_toml(r, source));
  out.files.emplace_back("calibration_stripe.toml.report.txt",
                         stripe_calibration_report(r, *sensor.stripe, source));
  return out;
}

}  // namespace rangefit::daemon
