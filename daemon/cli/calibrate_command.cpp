// `rangefit calibrate stripe|css|pantilt`: the cell's extrinsics from raw scans of a reference
// body (calib/). The result is never applied: it is written as a TOML fragment with the fields
// of the configuration it replaces, beside the configuration unless --out says where, with a
// report of residuals and uncertainties next to it; the operator reviews it and includes it.
// The stripe cell is here; css and pantilt are calibrate_css.cpp and calibrate_pan_tilt.cpp.
#include <Eigen/Geometry>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "calib/stripe_calibration.hpp"
#include "daemon/cli/calibrate_output.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/service/calibrate_request.hpp"

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
  // The same fragment and report as the service's calibrate request writes.
  const std::string source = "sweep " + a.scans[0];
  write_result(out_path(a, "calibration_stripe.toml"), daemon::stripe_calibration_toml(r, source),
               daemon::stripe_calibration_report(r, start, source));
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
