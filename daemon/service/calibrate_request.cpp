#include "daemon/service/calibrate_request.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
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

std::string stripe_calibration_toml(const calib::StripeRigResult& r,
                                    std::span<const StripeCameraStart> cameras,
                                    const std::string& source) {
  std::ostringstream toml;
  toml << "# rangefit stripe cell calibration, from " << source
       << "; see the .report.txt beside it. Not applied: include it in the configuration.\n"
       << "[fusion.stripe_cell]\n";
  for (std::size_t k = 0; k < r.cameras.size(); ++k) {
    if (!cameras[k].name.empty()) continue;
    const hal::StripeCellGeometry& g = r.cameras[k].geometry;
    toml << "ranger_position_cell_mm = " << toml_vec(g.ranger_position_cell_mm) << "\n"
         << "ranger_rpy_cell_rad = " << toml_vec(g.ranger_rpy_cell_rad) << "\n";
  }
  toml << "axis_direction_cell = " << toml_vec(r.cameras.front().geometry.axis_direction_cell)
       << "\n";
  for (std::size_t k = 0; k < r.cameras.size(); ++k) {
    if (cameras[k].name.empty()) continue;
    const hal::StripeCellGeometry& g = r.cameras[k].geometry;
    toml << "\n[[fusion.stripe_cell.cameras]]  # replaces the entry of this name\n"
         << "name = \"" << cameras[k].name << "\"\n"
         << "ranger_position_cell_mm = " << toml_vec(g.ranger_position_cell_mm) << "\n"
         << "ranger_rpy_cell_rad = " << toml_vec(g.ranger_rpy_cell_rad) << "\n"
         << "baseline_mm = " << g.ranger.baseline_mm << "\n";
  }
  return toml.str();
}

std::string stripe_calibration_report(const calib::StripeRigResult& r,
                                      std::span<const StripeCameraStart> cameras,
                                      const std::string& source) {
  std::ostringstream rep;
  rep.precision(4);
  rep << "stripe cell calibration (thesis 3.2), " << source << "\n";
  for (std::size_t k = 0; k < r.cameras.size(); ++k) {
    const calib::StripeCalibrationResult& c = r.cameras[k];
    const hal::StripeCellGeometry& g = c.geometry;
    const hal::StripeCellGeometry& start = cameras[k].start;
    const std::string indent = r.cameras.size() > 1 ? "    " : "  ";
    if (r.cameras.size() > 1) {
      rep << "  camera " << k + 1 << ", "
          << (cameras[k].name.empty() ? "the first ([fusion.stripe_cell])"
                                      : "\"" + cameras[k].name + "\"")
          << ":\n";
    }
    for (std::size_t i = 0; i < c.rounds.size(); ++i) {
      rep << indent << "linear round " << i + 1
          << (i == 3 ? " (piercing points averaged over the cameras)" : "") << ": corner rms "
          << c.rounds[i].corner_rms_mm << " mm, plane points";
      for (const auto n : c.rounds[i].plane_points) rep << " " << n;
      rep << "\n";
    }
    rep << indent << "plane points " << c.points << ", rms " << c.initial_rms_mm << " -> "
        << c.rms_mm << " mm\n"
        << indent << "ranger position " << toml_vec(g.ranger_position_cell_mm) << " mm (was "
        << toml_vec(start.ranger_position_cell_mm) << "), 1 sigma " << toml_vec(c.position_sigma_mm)
        << " mm\n"
        << indent << "ranger rpy " << toml_vec(g.ranger_rpy_cell_rad) << " rad (was "
        << toml_vec(start.ranger_rpy_cell_rad) << "), 1 sigma about its axes "
        << toml_vec(c.rotation_sigma_rad / kDeg) << " deg\n";
  }
  const calib::StripeCalibrationResult& first = r.cameras.front();
  rep << "  refinement: " << r.points << " plane points, rms " << r.initial_rms_mm << " -> "
      << r.rms_mm << " mm in " << r.lm_iterations << " iterations\n"
      << "  axis direction " << toml_vec(first.geometry.axis_direction_cell) << " (was "
      << toml_vec(cameras.front().start.axis_direction_cell) << "), 1 sigma "
      << first.axis_sigma_rad.x() / kDeg << ", " << first.axis_sigma_rad.y() / kDeg << " deg\n";
  return rep.str();
}

namespace {

// Why the cameras' sweeps cannot be solved together, or empty: one sweep per camera, all of the
// cube where this request says it is.
std::string check_rig(const std::vector<StripeCalibrationSweep>& all) {
  const CalibrationTarget& own = all.back().target;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const CalibrationTarget& t = all[i].target;
    if (t.edge_mm != own.edge_mm || t.bar_mm != own.bar_mm ||
        !t.T_table_target.isApprox(own.T_table_target, 1e-9)) {
      return "sweep " + std::to_string(i + 1) + " of " + std::to_string(all.size()) + " on " +
             all[i].sensor + " names another cube or cube pose than this one";
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (all[j].camera.name == all[i].camera.name) {
        return all[j].sensor + " and " + all[i].sensor + " are the same camera (" +
               (all[i].camera.name.empty() ? std::string("the first; name further ones in "
                                                         "[[fusion.stripe_cell.cameras]]")
                                           : all[i].camera.name) +
               "): one sweep per camera";
      }
    }
  }
  return "";
}

nlohmann::json camera_json(const calib::StripeCalibrationResult& c,
                           const StripeCalibrationSweep& s) {
  const hal::StripeCellGeometry& g = c.geometry;
  return {{"sensor", s.sensor},
          {"camera", s.camera.name},
          {"ranger_position_cell_mm", json_vec(g.ranger_position_cell_mm)},
          {"ranger_rpy_cell_rad", json_vec(g.ranger_rpy_cell_rad)},
          {"baseline_mm", g.ranger.baseline_mm},
          {"rms_mm", c.rms_mm},
          {"sigma",
           {{"position_mm", json_vec(c.position_sigma_mm)},
            {"rotation_rad", json_vec(c.rotation_sigma_rad)}}}};
}

}  // namespace

// The file a request's sweep of its k-th camera is spooled as (k from 0).
std::string raw_sweep_file(std::size_t k) {
  return k == 0 ? std::string("raw_sweep_stripe.txt")
                : "raw_sweep_stripe_" + std::to_string(k + 1) + ".txt";
}

namespace {

// One camera's sweep of this request, taken back from its fused scan; empty with *why set when
// it cannot be.
std::optional<StripeCalibrationSweep> own_sweep(const std::string& name, const PointCloud& cloud,
                                                const ScanSensor& sensor,
                                                const CalibrationTarget& target, std::string* why) {
  if (!sensor.stripe) {
    *why = name +
           ": the scan's sensor reports no stripe cell geometry (a stripe sweep on the cell is "
           "needed, not a replay)";
    return std::nullopt;
  }
  RawStripeProfiles raw = raw_stripe_profiles(in_fusion_frame(cloud, sensor), *sensor.stripe);
  if (!raw.error.empty()) {
    *why = name + ": " + raw.error;
    return std::nullopt;
  }
  StripeCalibrationSweep own{name, {sensor.stripe_camera, *sensor.stripe}, {}, target};
  own.sweep.kind = calib::SweepKind::kStripe;
  own.sweep.points_per_profile = sensor.stripe->ranger.points_per_profile;
  own.sweep.axis_mm = std::move(raw.axis_mm);
  own.sweep.profiles = std::move(raw.profiles);
  return own;
}

}  // namespace

DetectionResult calibrate_request(const PointCloud& cloud, const ScanRequest& request,
                                  const ScanSensor& sensor, std::span<const SensorScan> views,
                                  StripeCalibrationSweeps& sweeps, std::uint64_t default_seed) {
  // Validation admits only the stripe target, on stripe sensors. Several cameras in one request
  // each come apart (views); one comes as the scan itself.
  std::vector<StripeCalibrationSweep> own;
  std::string why;
  if (views.empty()) {
    if (auto s = own_sweep(request.sensor, cloud, sensor, request.target, &why)) {
      own.push_back(std::move(*s));
    }
  }
  for (const SensorScan& v : views) {
    auto s = own_sweep(v.name, v.cloud, v.sensor, request.target, &why);
    if (!s) break;
    own.push_back(std::move(*s));
  }
  if (!why.empty()) return DetectionResult::error(request, "calibrate stripe: " + why);
  DetectionResult out;
  out.details = {{"target", request.target.kind},
                 {"applied", false},
                 {"profiles", own.front().sweep.profiles.size()}};
  for (std::size_t k = 0; k < own.size(); ++k) {
    out.files.emplace_back(raw_sweep_file(k), calib::format_raw_sweep(own[k].sweep));
  }
  std::string unknown;
  const std::size_t own_cameras = own.size();
  std::vector<StripeCalibrationSweep> all;
  for (auto& earlier : sweeps.join(request.id, std::move(own), request.target.scans, &unknown)) {
    for (auto& s : earlier) all.push_back(std::move(s));
  }
  if (!unknown.empty()) {
    out.reason = std::string(kNotCalibrated) +
                 unknown_record_reason("stripe", unknown, "raw_sweep_stripe.txt");
    return out;
  }
  if (const std::string no_rig = check_rig(all); !no_rig.empty()) {
    out.reason = std::string(kNotCalibrated) + no_rig;
    return out;
  }
  calib::StripeRigInput in;
  std::vector<StripeCameraStart> cameras;
  for (const StripeCalibrationSweep& s : all) {
    in.cameras.push_back({s.sweep.profiles, s.sweep.axis_mm, s.camera.start});
    cameras.push_back(s.camera);
  }
  in.cube = {request.target.edge_mm, request.target.bar_mm};
  in.T_table_cube = request.target.T_table_target;
  calib::StripeCalibrationOptions options;
  options.planes.seed = request.seed != 0 ? request.seed : default_seed;
  const calib::StripeRigResult r = calib::calibrate_stripe_rig(in, options);
  out.details["cameras"] = all.size();
  if (!r.ok) {
    out.reason = std::string(kNotCalibrated) + r.reason;
    return out;
  }
  out.found = true;
  // This request's sensor: its first camera, after the earlier requests' cameras.
  const calib::StripeCalibrationResult& mine = r.cameras[all.size() - own_cameras];
  out.details["rms_mm"] = r.rms_mm;
  out.details["initial_rms_mm"] = r.initial_rms_mm;
  out.details["plane_points"] = r.points;
  out.details["fusion.stripe_cell"] = {
      {"ranger_position_cell_mm", json_vec(mine.geometry.ranger_position_cell_mm)},
      {"ranger_rpy_cell_rad", json_vec(mine.geometry.ranger_rpy_cell_rad)},
      {"axis_direction_cell", json_vec(mine.geometry.axis_direction_cell)}};
  out.details["sigma"] = {{"position_mm", json_vec(mine.position_sigma_mm)},
                          {"rotation_rad", json_vec(mine.rotation_sigma_rad)},
                          {"axis_rad", {mine.axis_sigma_rad.x(), mine.axis_sigma_rad.y()}}};
  if (all.size() > 1) {
    nlohmann::json each = nlohmann::json::array();
    for (std::size_t k = 0; k < all.size(); ++k) each.push_back(camera_json(r.cameras[k], all[k]));
    out.details["stripe_cameras"] = each;
  }
  // Each ranger's pose in the cell as a part, so the result can be drawn and published.
  for (std::size_t k = 0; k < all.size(); ++k) {
    out.parts.push_back({all.size() > 1 ? "ranger_" + all[k].sensor : std::string("ranger"),
                         r.cameras[k].geometry.T_cell_ranger(), 1.0, 0});
  }
  std::string source = "rangefitd request " + request.id + " on ";
  for (std::size_t k = all.size() - own_cameras; k < all.size(); ++k) {
    source += (k + own_cameras == all.size() ? "" : ", ") + all[k].sensor;
  }
  for (std::size_t k = 0; k < request.target.scans.size(); ++k) {
    source += (k == 0 ? " with " : ", ") + request.target.scans[k];
  }
  out.files.emplace_back("calibration_stripe.toml", stripe_calibration_toml(r, cameras, source));
  out.files.emplace_back("calibration_stripe.toml.report.txt",
                         stripe_calibration_report(r, cameras, source));
  return out;
}

}  // namespace rangefit::daemon
