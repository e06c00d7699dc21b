// `rangefit calibrate css`: the CSS mount on the robot's last joint and the joint's zero offset
// (calib/css_calibration.hpp) from sphere scans at several robot poses (calib/css_scan_text.hpp).
// Writes the [fusion.css] fields the configuration holds (omega_zero_rad, eta_rad,
// pivot_radius_mm) and reports the full mount, the part of it that form cannot hold, and the
// bore-axis error the calibration leaves.
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "calib/css_scan_text.hpp"
#include "calib/stripe_calibration.hpp"
#include "daemon/cli/calibrate_output.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"

namespace rangefit::cli::calibrate {
namespace {

// Mount parts the [fusion.css] form (eta about x, pivot radius along z) cannot hold and that
// matter next to the calibration's accuracy (0.05 mm / 0.02 deg).
constexpr double kOffFormMm = 0.05, kOffFormRad = 0.02 * kDeg;

int run_css(const CommonArgs& a, double radius) {
  std::vector<calib::CssSphereScan> scans;
  for (const std::string& path : a.scans) {
    calib::CssScansParse p = calib::parse_css_scans(read_text(path), path);
    if (!p.scans) throw std::runtime_error(p.error);
    scans.insert(scans.end(), p.scans->begin(), p.scans->end());
  }
  const fusion::FusionConfig config = start_config(a);
  const hal::CssGeometry& start = config.css.geometry;
  calib::CssCalibrationOptions options;
  options.sphere_radius_mm = radius;
  const calib::CssCalibrationResult r =
      calib::calibrate_css_mount(scans, start, config.css.omega_zero_rad, options);
  if (!r.ok) {
    std::cerr << "rangefit calibrate css: " << r.reason << "\n";
    return kExitNotFound;
  }
  std::ostringstream toml, rep;
  toml.precision(12);
  toml << "# rangefit calibrate css, from " << scans.size()
       << " sphere scans; see the .report.txt beside it\n"
       << "[fusion.css]\n"
       << "omega_zero_rad = " << r.omega_zero_rad << "\n"
       << "eta_rad = " << r.eta_rad << "\n"
       << "pivot_radius_mm = " << r.pivot_radius_mm << "\n";
  const Eigen::Vector3d rpy =
      calib::rpy_of(r.T_joint_css.linear(), Eigen::Vector3d(start.eta_rad, 0.0, 0.0));
  rep.precision(5);
  rep << "CSS mount calibration (hand-eye, sphere of radius " << radius << " mm), " << scans.size()
      << " robot poses, " << r.samples << " samples\n"
      << "  range rms " << r.initial_rms_mm << " -> " << r.rms_mm << " mm in " << r.iterations
      << " iterations\n"
      << "  omega_zero " << r.omega_zero_rad << " rad (was " << config.css.omega_zero_rad
      << "), 1 sigma " << std::sqrt(r.covariance(0, 0)) / kDeg << " deg\n"
      << "  eta " << r.eta_rad << " rad (was " << start.eta_rad << "), pivot radius "
      << r.pivot_radius_mm << " mm (was " << start.pivot_radius_mm << ")\n"
      << "  full mount on the joint: position " << vec(r.T_joint_css.translation()) << " mm, rpy "
      << vec(rpy) << " rad; 1 sigma y, z " << std::sqrt(r.covariance(1, 1)) << ", "
      << std::sqrt(r.covariance(2, 2)) << " mm, rotation "
      << vec(r.covariance.diagonal().segment<3>(3).cwiseSqrt() / kDeg) << " deg\n"
      << "  sphere centre " << vec(r.sphere_centre_mm) << " mm (robot base)\n"
      << "  a bore measured along the sensor axis inherits 1 sigma " << r.axis_sigma_rad / kDeg
      << " deg in its axis and " << vec(r.origin_sigma_mm) << " mm in its position\n"
      << "  mount off the configurable form by " << r.mount_off_form_mm << " mm, "
      << r.mount_off_form_rad / kDeg << " deg";
  if (r.mount_off_form_mm > kOffFormMm || r.mount_off_form_rad > kOffFormRad) {
    rep << " -- WARNING: more than the calibration's accuracy; [fusion.css] holds only eta and the "
           "pivot radius, so detections keep this error";
  }
  rep << "\n";
  write_result(out_path(a, "calibration_css.toml"), toml.str(), rep.str());
  return kExitOk;
}

}  // namespace

void add_calibrate_css(CLI::App* calibrate, int* exit_code) {
  auto* s = calibrate->add_subcommand(
      "css",
      "CSS mount on the last joint and the joint zero from sphere scans at several robot poses "
      "(calib/css_scan_text.hpp)");
  struct Args {
    CommonArgs common;
    double radius = 0.0;
  };
  auto a = std::make_shared<Args>();
  add_common(s, a->common, "sphere scan file(s) (calib/css_scan_text.hpp)");
  s->add_option("--sphere-radius", a->radius, "certified radius of the reference sphere (mm)")
      ->required()
      ->check(finite_range(0.1, 1e4));
  on_run(s, exit_code, [a] { return run_css(a->common, a->radius); });
}

}  // namespace rangefit::cli::calibrate
