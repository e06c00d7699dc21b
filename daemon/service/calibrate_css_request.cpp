#include "daemon/service/calibrate_css_request.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "calib/css_scan_text.hpp"
#include "calib/stripe_calibration.hpp"
#include "daemon/service/calibrate_request.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/request_validation.hpp"
#include "detect/common/angles.hpp"
#include "hal/samples.hpp"

namespace rangefit::daemon {
namespace {

// Mount parts the [fusion.css] form (eta about x, pivot radius along z) cannot hold and that
// matter next to the calibration's accuracy (0.05 mm / 0.02 deg).
constexpr double kOffFormMm = 0.05, kOffFormRad = 0.02 * kDeg;
// A point fusion made is taken back to well under the sensor's resolution; one that is not was
// not made with this geometry.
constexpr double kInverseToleranceMm = 1e-6;

struct Inverse {
  double omega = 0.0, range = 0.0;
  bool ok = false;
};

// omega, range with R_y(omega) (L + range b) = p, by Gauss-Newton from omega0.
Inverse invert(const Eigen::Vector3d& p, const Eigen::Vector3d& L, const Eigen::Vector3d& b,
               double omega0) {
  Inverse x;
  x.omega = omega0;
  const auto rotate = [](double w, const Eigen::Vector3d& q) {
    const double c = std::cos(w), s = std::sin(w);
    return Eigen::Vector3d(c * q.x() + s * q.z(), q.y(), c * q.z() - s * q.x());
  };
  x.range = (p - rotate(x.omega, L)).norm();
  for (int it = 0; it < 20; ++it) {
    const Eigen::Vector3d q = L + x.range * b;
    const double c = std::cos(x.omega), s = std::sin(x.omega);
    const Eigen::Vector3d f = rotate(x.omega, q) - p;
    Eigen::Matrix<double, 3, 2> J;
    J.col(0) = Eigen::Vector3d(-s * q.x() + c * q.z(), 0.0, -s * q.z() - c * q.x());
    J.col(1) = rotate(x.omega, b);
    const Eigen::Vector2d step = (J.transpose() * J).ldlt().solve(-J.transpose() * f);
    x.omega += step.x();
    x.range += step.y();
    if (step.cwiseAbs().maxCoeff() < 1e-13) break;
  }
  x.ok = std::isfinite(x.omega) && std::isfinite(x.range) &&
         (rotate(x.omega, L + x.range * b) - p).norm() < kInverseToleranceMm;
  return x;
}

}  // namespace

CssRawSamples css_raw_samples(const PointCloud& cloud, const ScanSensor::CssFusion& css) {
  CssRawSamples out;
  constexpr int kCols = hal::CssRevolution::kSamples;
  if (cloud.grid.cols != kCols ||
      cloud.grid.index.size() != static_cast<std::size_t>(cloud.grid.rows) * kCols) {
    out.error = "the scan is not organised in CSS revolutions";
    return out;
  }
  const hal::CssGeometry& g = css.geometry;
  const Eigen::Isometry3d mount = g.T_world_css(0.0);
  const Eigen::Vector3d L = mount * g.laser_point();
  std::array<Eigen::Vector3d, kCols> beams;  // of each sample column, in the joint frame
  for (int i = 0; i < kCols; ++i)
    beams[i] = mount.linear() * g.beam_direction(g.beam_angle(i, kCols));
  std::size_t failed = 0;
  for (int r = 0; r < cloud.grid.rows; ++r) {
    double omega = 0.0;
    for (int i = 0; i < kCols; ++i) {
      const std::int32_t k = cloud.grid.at(r, i);
      if (k < 0 || static_cast<std::size_t>(k) >= cloud.points.size()) continue;
      const Inverse x = invert(cloud.points[static_cast<std::size_t>(k)], L,
                               beams[static_cast<std::size_t>(i)], omega);
      if (!x.ok) {
        ++failed;
        continue;
      }
      omega = x.omega;
      out.samples.push_back({x.omega + css.omega_zero_rad, g.beam_angle(i, kCols), x.range});
    }
  }
  if (failed > out.samples.size() / 100) {
    out.error = std::to_string(failed) +
                " points are not where the configured CSS geometry puts any sample (a scan "
                "fused with another geometry?)";
  } else if (out.samples.empty()) {
    out.error = "the scan has no points";
  }
  return out;
}

std::string css_calibration_toml(const calib::CssCalibrationResult& r, std::size_t poses,
                                 const std::string& source) {
  std::ostringstream toml;
  toml.precision(12);
  toml << "# rangefit CSS mount calibration, from " << poses << " sphere scans (" << source
       << "); see the .report.txt beside it. Not applied: include it in the configuration.\n"
       << "[fusion.css]\n"
       << "omega_zero_rad = " << r.omega_zero_rad << "\n"
       << "eta_rad = " << r.eta_rad << "\n"
       << "pivot_radius_mm = " << r.pivot_radius_mm << "\n";
  return toml.str();
}

std::string css_calibration_report(const calib::CssCalibrationResult& r,
                                   const hal::CssGeometry& start, double omega_zero_start,
                                   double radius_mm, std::size_t poses, const std::string& source) {
  const Eigen::Vector3d rpy =
      calib::rpy_of(r.T_joint_css.linear(), Eigen::Vector3d(start.eta_rad, 0.0, 0.0));
  std::ostringstream rep;
  rep.precision(5);
  rep << "CSS mount calibration (hand-eye, sphere of radius " << radius_mm << " mm), " << poses
      << " robot poses, " << r.samples << " samples (" << r.rejected
      << " more left out, not on the sphere), " << source << "\n"
      << "  range rms " << r.initial_rms_mm << " -> " << r.rms_mm << " mm in " << r.iterations
      << " iterations\n"
      << "  omega_zero " << r.omega_zero_rad << " rad (was " << omega_zero_start << "), 1 sigma "
      << std::sqrt(r.covariance(0, 0)) / kDeg << " deg\n"
      << "  eta " << r.eta_rad << " rad (was " << start.eta_rad << "), pivot radius "
      << r.pivot_radius_mm << " mm (was " << start.pivot_radius_mm << ")\n"
      << "  full mount on the joint: position " << toml_vec(r.T_joint_css.translation())
      << " mm, rpy " << toml_vec(rpy) << " rad; 1 sigma y, z " << std::sqrt(r.covariance(1, 1))
      << ", " << std::sqrt(r.covariance(2, 2)) << " mm, rotation "
      << toml_vec(r.covariance.diagonal().segment<3>(3).cwiseSqrt() / kDeg) << " deg\n"
      << "  sphere centre " << toml_vec(r.sphere_centre_mm) << " mm (robot base)\n"
      << "  a bore measured along the sensor axis inherits 1 sigma " << r.axis_sigma_rad / kDeg
      << " deg in its axis and " << toml_vec(r.origin_sigma_mm) << " mm in its position\n"
      << "  mount off the configurable form by " << r.mount_off_form_mm << " mm, "
      << r.mount_off_form_rad / kDeg << " deg";
  if (r.mount_off_form_mm > kOffFormMm || r.mount_off_form_rad > kOffFormRad) {
    rep << " -- WARNING: more than the calibration's accuracy; [fusion.css] holds only eta and the "
           "pivot radius, so detections keep this error";
  }
  rep << "\n";
  return rep.str();
}

DetectionResult calibrate_css_request(const PointCloud& cloud, const ScanRequest& request,
                                      const ScanSensor& sensor, CssCalibrationPoses& poses) {
  // Validation admits the css target only on a css sensor, with a robot pose and a radius.
  const CalibrationTarget& target = request.target;
  if (!sensor.css || !target.T_base_joint) {
    return DetectionResult::error(request,
                                  "calibrate css: the scan's sensor reports no CSS geometry (a "
                                  "CSS scan on the cell is needed, not a replay)");
  }
  CssRawSamples raw = css_raw_samples(in_fusion_frame(cloud, sensor), *sensor.css);
  if (!raw.error.empty()) return DetectionResult::error(request, "calibrate css: " + raw.error);

  calib::CssSphereScan own{*target.T_base_joint, std::move(raw.samples)};
  DetectionResult out;
  out.details = {{"target", target.kind}, {"applied", false}, {"samples", own.samples.size()}};
  // This pose's samples, in the file `rangefit calibrate css --scans` reads.
  out.files.emplace_back("css_sphere_scan.txt", calib::format_css_scans({own}));
  std::string unknown;
  const std::vector<calib::CssSphereScan> scans =
      poses.join(request.id, std::move(own), target.scans, &unknown);
  if (!unknown.empty()) {
    out.reason =
        std::string(kNotCalibrated) + unknown_record_reason("css", unknown, "css_sphere_scan.txt");
    return out;
  }
  out.details["poses"] = scans.size();
  if (scans.size() < 3) {
    out.reason = std::string(kNotCalibrated) + "pose recorded; " + std::to_string(scans.size()) +
                 " of at least 3 robot poses: name this request's id in the next one's scans";
    return out;
  }
  const hal::CssGeometry& start = sensor.css->geometry;
  calib::CssCalibrationOptions options;
  options.sphere_radius_mm = target.radius_mm;
  const calib::CssCalibrationResult r =
      calib::calibrate_css_mount(scans, start, sensor.css->omega_zero_rad, options);
  if (!r.ok) {
    out.reason = std::string(kNotCalibrated) + r.reason;
    return out;
  }
  out.found = true;
  out.details["rms_mm"] = r.rms_mm;
  out.details["initial_rms_mm"] = r.initial_rms_mm;
  out.details["rejected_samples"] = r.rejected;
  out.details["fusion.css"] = {{"omega_zero_rad", r.omega_zero_rad},
                               {"eta_rad", r.eta_rad},
                               {"pivot_radius_mm", r.pivot_radius_mm}};
  out.details["mount"] = {
      {"position_mm", json_vec(r.T_joint_css.translation())},
      {"rpy_rad",
       json_vec(calib::rpy_of(r.T_joint_css.linear(), Eigen::Vector3d(start.eta_rad, 0.0, 0.0)))},
      {"off_form_mm", r.mount_off_form_mm},
      {"off_form_rad", r.mount_off_form_rad}};
  out.details["sphere_centre_mm"] = json_vec(r.sphere_centre_mm);
  out.details["sigma"] = {{"omega_zero_rad", std::sqrt(r.covariance(0, 0))},
                          {"axis_rad", r.axis_sigma_rad},
                          {"origin_mm", json_vec(r.origin_sigma_mm)}};
  // The sensor on the joint at this pose's scan centre, so the result can be drawn and published.
  out.parts.push_back({"css", *target.T_base_joint * r.T_joint_css, 1.0, 0});
  const std::string source = "rangefitd request " + request.id + " on " + request.sensor;
  out.files.emplace_back("calibration_css.toml", css_calibration_toml(r, scans.size(), source));
  out.files.emplace_back("calibration_css.toml.report.txt",
                         css_calibration_report(r, start, sensor.css->omega_zero_rad,
                                                target.radius_mm, scans.size(), source));
  return out;
}

}  // namespace rangefit::daemon
