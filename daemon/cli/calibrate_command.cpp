// `rangefit calibrate stripe|css|pantilt`: the cell's extrinsics from raw scans of a reference
// body (calib/). The result is never applied: it is written as a TOML fragment with the fields
// of the configuration it replaces, beside the configuration unless --out says where, with a
// report of residuals and uncertainties next to it; the operator reviews it and includes it.
// The stripe cell is here; css and pantilt are calibrate_css.cpp and calibrate_pan_tilt.cpp.
#include <Eigen/Geometry>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "calib/stripe_calibration.hpp"
#include "daemon/cli/calibrate_output.hpp"
#include "daemon/cli/commands.hpp"

namespace rangefit::cli {
namespace {

using namespace calibrate;

int run_stripe(const CommonArgs& a, const std::vector<double>& cube,
               const std::vector<double>& pose) {
  if (a.scans.size() != 1) throw std::runtime_error("stripe: exactly one --scans sweep");
  const calib::RawSweep sweep = load_sweep(a.scans[0], calib::SweepKind::kStripe);
  const fusion::FusionConfig config = start_config(a);
  const hal::StripeCellGeometry& start = config.stripe_cell.geometry;
  calib::StripeCalibrationInput in;
  in.profiles = sweep.profiles;
  in.axis_mm = sweep.axis_mm;
  in.cube = {cube[0], cube[1]};
  in.T_table_cube = pose_of(pose);
  calib::StripeCalibrationOptions options;
  options.planes.seed = a.seed;
  const calib::StripeCalibrationResult r = calib::calibrate_stripe_cell(in, start, options);
  if (!r.ok) {
    std::cerr << "rangefit calibrate stripe: " << r.reason << "\n";
    return kExitNotFound;
  }
  const hal::StripeCellGeometry& g = r.geometry;
  std::ostringstream toml, rep;
  toml << "# rangefit calibrate stripe, from " << a.scans[0] << "; see the .report.txt beside it\n"
       << "[fusion.stripe_cell]\n"
       << "ranger_position_cell_mm = " << vec(g.ranger_position_cell_mm) << "\n"
       << "ranger_rpy_cell_rad = " << vec(g.ranger_rpy_cell_rad) << "\n"
       << "axis_direction_cell = " << vec(g.axis_direction_cell) << "\n";
  rep.precision(4);
  rep << "stripe cell calibration (thesis 3.2), sweep " << a.scans[0] << "\n";
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    rep << "  linear round " << i + 1 << ": corner rms " << r.rounds[i].corner_rms_mm
        << " mm, plane points";
    for (const auto n : r.rounds[i].plane_points) rep << " " << n;
    rep << "\n";
  }
  rep << "  refinement: " << r.points << " plane points, rms " << r.initial_rms_mm << " -> "
      << r.rms_mm << " mm in " << r.lm_iterations << " iterations\n"
      << "  ranger position " << vec(g.ranger_position_cell_mm) << " mm (was "
      << vec(start.ranger_position_cell_mm) << "), 1 sigma " << vec(r.position_sigma_mm) << " mm\n"
      << "  ranger rpy " << vec(g.ranger_rpy_cell_rad) << " rad (was "
      << vec(start.ranger_rpy_cell_rad) << "), 1 sigma about its axes "
      << vec(r.rotation_sigma_rad / kDeg) << " deg\n"
      << "  axis direction " << vec(g.axis_direction_cell) << " (was "
      << vec(start.axis_direction_cell) << "), 1 sigma " << r.axis_sigma_rad.x() / kDeg << ", "
      << r.axis_sigma_rad.y() / kDeg << " deg\n";
  write_result(out_path(a, "calibration_stripe.toml"), toml.str(), rep.str());
  return kExitOk;
}

}  // namespace

void add_calibrate_command(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand(
      "calibrate",
      "estimate the cell's extrinsics from scans of a reference body (written for "
      "review, never applied)");
  cmd->require_subcommand(1);
  {
    auto* s = cmd->add_subcommand("stripe",
                                  "stripe cell from one sweep over the hollow calibration cube");
    struct Args {
      CommonArgs common;
      std::vector<double> cube{120.0, 12.0}, pose;
    };
    auto a = std::make_shared<Args>();
    add_common(s, a->common, "one raw stripe sweep (calib/raw_sweep_text.hpp)");
    add_cube_options(s, a->cube, a->pose, "table");
    on_run(s, exit_code, [a] { return run_stripe(a->common, a->cube, a->pose); });
  }
  add_calibrate_css(cmd, exit_code);
  add_calibrate_pan_tilt(cmd, exit_code);
}

}  // namespace rangefit::cli
