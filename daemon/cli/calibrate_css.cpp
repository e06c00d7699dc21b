// `rangefit calibrate css`: the CSS mount on the robot's last joint and the joint's zero offset
// (calib/css_calibration.hpp) from sphere scans at several robot poses (calib/css_scan_text.hpp).
// Writes the [fusion.css] fields the configuration holds (omega_zero_rad, eta_rad,
// pivot_radius_mm) and reports the full mount, the part of it that form cannot hold, and the
// bore-axis error the calibration leaves.
#include <iostream>
#include <memory>
#include <stdexcept>

#include "calib/css_scan_text.hpp"
#include "daemon/cli/calibrate_output.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "daemon/service/calibrate_css_request.hpp"

namespace rangefit::cli::calibrate {
namespace {

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
  const std::string source = "rangefit calibrate css";
  write_result(out_path(a, "calibration_css.toml"),
               daemon::css_calibration_toml(r, scans.size(), source),
               daemon::css_calibration_report(r, start, config.css.omega_zero_rad, radius,
                                              scans.size(), source));
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
