#include "daemon/service/calibrate_pan_tilt_request.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "daemon/service/calibrate_request.hpp"
#include "daemon/service/json_codec.hpp"
#include "detect/common/angles.hpp"

namespace rangefit::daemon {
namespace {

// A point fusion placed is taken back into the laser plane to well under the ranger's
// resolution; one that is not was not placed with this geometry and pose.
constexpr double kPlaneToleranceMm = 1e-4;
// The tilt the head reports may differ from the one the cell program holds by the drive's
// following error, not by more.
constexpr double kTiltToleranceRad = 0.5 * kDeg;

}  // namespace

RawPanTiltSweep raw_pan_tilt_sweep(const PointCloud& cloud, const ScanSensor& sensor) {
  RawPanTiltSweep out;
  if (!sensor.pan_tilt) {
    out.error = "the scan's sensor reports no pan-tilt geometry";
    return out;
  }
  if (cloud.grid.empty() ||
      cloud.grid.index.size() != static_cast<std::size_t>(cloud.grid.rows) * cloud.grid.cols ||
      sensor.row_poses.size() != static_cast<std::size_t>(cloud.grid.rows)) {
    out.error = "the scan is not organised in profiles with their pan and tilt";
    return out;
  }
  const hal::PanTiltGeometry& g = *sensor.pan_tilt;
  calib::RawSweep& sweep = out.sweep;
  sweep.kind = calib::SweepKind::kPanTilt;
  sweep.points_per_profile = cloud.grid.cols;
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  std::size_t off_plane = 0, points = 0;
  for (int r = 0; r < cloud.grid.rows; ++r) {
    const auto& [pan, tilt] = sensor.row_poses[static_cast<std::size_t>(r)];
    const Eigen::Isometry3d T_ranger_world = g.T_world_ranger(pan, tilt).inverse();
    hal::RangerProfile p;
    p.sequence = static_cast<std::uint32_t>(r);
    p.x_mm.assign(static_cast<std::size_t>(cloud.grid.cols), kNaN);
    p.z_mm.assign(static_cast<std::size_t>(cloud.grid.cols), kNaN);
    for (int c = 0; c < cloud.grid.cols; ++c) {
      const std::int32_t i = cloud.grid.at(r, c);
      if (i < 0 || static_cast<std::size_t>(i) >= cloud.points.size()) continue;
      const Eigen::Vector3d q = T_ranger_world * cloud.points[static_cast<std::size_t>(i)];
      ++points;
      if (!(std::abs(q.y()) < kPlaneToleranceMm)) {
        ++off_plane;
        continue;
      }
      p.x_mm[static_cast<std::size_t>(c)] = static_cast<float>(q.x());
      p.z_mm[static_cast<std::size_t>(c)] = static_cast<float>(q.z());
    }
    hal::PanTiltSample a;
    a.pan_rad = pan;
    a.tilt_rad = tilt;
    sweep.angles.push_back(a);
    sweep.profiles.push_back(std::move(p));
  }
  if (points == 0) {
    out.error = "the scan has no points";
  } else if (off_plane > points / 100) {
    out.error = std::to_string(off_plane) +
                " points are off the laser plane of their profile's pose (a scan fused with "
                "another geometry?)";
  }
  return out;
}

std::string pan_tilt_calibration_toml(const calib::PanTiltCalibrationResult& r, std::size_t sweeps,
                                      const std::string& source) {
  const hal::PanTiltGeometry& g = r.geometry;
  std::ostringstream toml;
  toml.precision(12);
  toml << "# rangefit pan-tilt head calibration, from " << sweeps << " sweeps (" << source
       << "); see the .report.txt beside it. Not applied: include it in the configuration.\n"
       << "[fusion.pan_tilt]\n"
       << "t_s_mm = " << toml_vec(g.t_s_mm) << "\n"
       << "t_w_mm = " << toml_vec(g.t_w_mm) << "\n"
       << "pan_zero_rad = " << g.pan_zero_rad << "\n"
       << "tilt_zero_rad = " << g.tilt_zero_rad << "\n";
  return toml.str();
}

std::string pan_tilt_calibration_report(const calib::PanTiltCalibrationResult& r,
                                        const hal::PanTiltGeometry& start, std::size_t sweeps,
                                        const std::string& source) {
  const hal::PanTiltGeometry& g = r.geometry;
  std::ostringstream rep;
  rep.precision(5);
  rep << "pan-tilt head calibration (eq. 5.7), " << sweeps << " sweeps, " << source << "\n";
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    rep << "  round " << i + 1 << ": " << r.rounds[i].plane_points << " plane points, rms "
        << r.rounds[i].rms_mm << " mm\n";
  }
  rep << "  plane rms " << r.initial_rms_mm << " -> " << r.rms_mm << " mm in " << r.lm_iterations
      << " iterations\n"
      << "  t_s " << toml_vec(g.t_s_mm) << " mm (was " << toml_vec(start.t_s_mm) << "), 1 sigma "
      << toml_vec(r.t_s_sigma_mm) << " mm\n"
      << "  t_w " << toml_vec(g.t_w_mm) << " mm (was " << toml_vec(start.t_w_mm) << "), 1 sigma "
      << toml_vec(r.t_w_sigma_mm) << " mm\n"
      << "  pan zero " << g.pan_zero_rad << " rad (was " << start.pan_zero_rad << "), 1 sigma "
      << r.zero_sigma_rad.x() / kDeg << " deg\n"
      << "  tilt zero " << g.tilt_zero_rad << " rad (was " << start.tilt_zero_rad << "), 1 sigma "
      << r.zero_sigma_rad.y() / kDeg << " deg\n";
  return rep.str();
}

DetectionResult calibrate_pan_tilt_request(const PointCloud& cloud, const ScanRequest& request,
                                           const ScanSensor& sensor,
                                           PanTiltCalibrationSweeps& sweeps,
                                           std::uint64_t default_seed) {
  const CalibrationTarget& target = request.target;
  RawPanTiltSweep raw = raw_pan_tilt_sweep(in_fusion_frame(cloud, sensor), sensor);
  if (!raw.error.empty()) return DetectionResult::error(request, "calibrate pantilt: " + raw.error);
  double tilt = 0.0;
  for (const auto& a : raw.sweep.angles) tilt += a.tilt_rad;
  tilt /= static_cast<double>(raw.sweep.angles.size());
  DetectionResult out;
  out.details = {{"target", target.kind},
                 {"applied", false},
                 {"profiles", raw.sweep.profiles.size()},
                 {"tilt_rad", tilt}};
  if (target.tilt_rad && !(std::abs(tilt - *target.tilt_rad) <= kTiltToleranceRad)) {
    std::ostringstream why;
    why << "calibrate pantilt: the head reports tilt " << tilt << " rad, the request says "
        << *target.tilt_rad << " rad: the cell program did not hold the tilt";
    return DetectionResult::error(request, why.str());
  }
  // This sweep, in the file `rangefit calibrate pantilt --scans` reads.
  out.files.emplace_back("raw_sweep_pantilt.txt", calib::format_raw_sweep(raw.sweep));
  std::string unknown;
  const std::vector<calib::RawSweep> all =
      sweeps.join(request.id, std::move(raw.sweep), target.scans, &unknown);
  if (!unknown.empty()) {
    out.reason = std::string(kNotCalibrated) +
                 unknown_record_reason("pantilt", unknown, "raw_sweep_pantilt.txt");
    return out;
  }
  out.details["sweeps"] = all.size();
  if (all.size() < 2) {
    out.reason = std::string(kNotCalibrated) +
                 "sweep recorded; 1 of at least 2 tilts: name this request's id in the scans of "
                 "the next one, at another tilt";
    return out;
  }
  calib::PanTiltCalibrationInput in;
  for (const calib::RawSweep& s : all) in.sweeps.push_back({s.profiles, s.angles});
  in.cube = {target.edge_mm, target.bar_mm};
  in.T_world_cube = target.T_table_target;
  calib::PanTiltCalibrationOptions options;
  options.planes.seed = request.seed != 0 ? request.seed : default_seed;
  const hal::PanTiltGeometry& start = *sensor.pan_tilt;
  const calib::PanTiltCalibrationResult r = calib::calibrate_pan_tilt(in, start, options);
  if (!r.ok) {
    out.reason = std::string(kNotCalibrated) + r.reason;
    return out;
  }
  const hal::PanTiltGeometry& g = r.geometry;
  out.found = true;
  out.details["rms_mm"] = r.rms_mm;
  out.details["initial_rms_mm"] = r.initial_rms_mm;
  out.details["plane_points"] = r.points;
  out.details["fusion.pan_tilt"] = {{"t_s_mm", json_vec(g.t_s_mm)},
                                    {"t_w_mm", json_vec(g.t_w_mm)},
                                    {"pan_zero_rad", g.pan_zero_rad},
                                    {"tilt_zero_rad", g.tilt_zero_rad}};
  out.details["sigma"] = {{"t_s_mm", json_vec(r.t_s_sigma_mm)},
                          {"t_w_mm", json_vec(r.t_w_sigma_mm)},
                          {"zeros_rad", {r.zero_sigma_rad.x(), r.zero_sigma_rad.y()}}};
  // The ranger at the head's zero pose, so the result can be drawn and published.
  out.parts.push_back(
      {"ranger", sensor.T_scan_fusion * g.T_world_ranger(g.pan_zero_rad, g.tilt_zero_rad), 1.0, 0});
  const std::string source = "rangefitd request " + request.id + " on " + request.sensor;
  out.files.emplace_back("calibration_pantilt.toml",
                         pan_tilt_calibration_toml(r, all.size(), source));
  out.files.emplace_back("calibration_pantilt.toml.report.txt",
                         pan_tilt_calibration_report(r, start, all.size(), source));
  return out;
}

}  // namespace rangefit::daemon
