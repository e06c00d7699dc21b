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
  const fusion::FusionConfig config = start_config(a);
  const fusion::StripeCellFusionConfig& cell = config.stripe_cell;
  // Sweep k is camera k: the first [fusion.stripe_cell], then [[fusion.stripe_cell.cameras]].
  if (a.scans.size() > 1 + cell.cameras.size()) {
    throw std::runtime_error("stripe: " + std::to_string(a.scans.size()) +
                             " sweeps, but the configuration has " +
                             std::to_string(1 + cell.cameras.size()) +
                             " camera(s) ([fusion.stripe_cell] and "
                             "[[fusion.stripe_cell.cameras]]), one sweep each");
  }
  std::vector<calib::RawSweep> sweeps;
  std::vector<daemon::StripeCameraStart> cameras;
  calib::StripeRigInput in;
  for (std::size_t k = 0; k < a.scans.size(); ++k) {
    sweeps.push_back(load_sweep(a.scans[k], calib::SweepKind::kStripe));
    const std::string name = k == 0 ? std::string() : cell.cameras[k - 1].name;
    cameras.push_back({name, fusion::stripe_cell_for(cell, name).geometry});
  }
  for (std::size_t k = 0; k < sweeps.size(); ++k) {
    in.cameras.push_back({sweeps[k].profiles, sweeps[k].axis_mm, cameras[k].start});
  }
  in.cube = {cube[0], cube[1]};
  in.T_table_cube = pose_of(pose);
  calib::StripeCalibrationOptions options;
  options.planes.seed = a.seed;
  const calib::StripeRigResult r = calib::calibrate_stripe_rig(in, options);
  if (!r.ok) {
    std::cerr << "rangefit calibrate stripe: " << r.reason << "\n";
    return kExitNotFound;
  }
  // The same fragment and report as the service's calibrate request writes.
  std::string source = a.scans.size() > 1 ? "sweeps" : "sweep";
  for (const std::string& s : a.scans) source += " " + s;
  write_result(out_path(a, "calibration_stripe.toml"),
               daemon::stripe_calibration_toml(r, cameras, source),
               daemon::stripe_calibration_report(r, cameras, source));
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
    auto* s = cmd->add_subcommand(
        "stripe",
        "stripe cell from a sweep over the hollow calibration cube, or one per camera of the "
        "laser plane");
    struct Args {
      CommonArgs common;
      std::vector<double> cube{120.0, 12.0}, pose;
    };
    auto a = std::make_shared<Args>();
    add_common(s, a->common,
               "raw stripe sweep (calib/raw_sweep_text.hpp); one per camera, the first camera's "
               "first, then those of [[fusion.stripe_cell.cameras]] in order");
    add_cube_options(s, a->cube, a->pose, "table");
    on_run(s, exit_code, [a] { return run_stripe(a->common, a->cube, a->pose); });
  }
  add_calibrate_css(cmd, exit_code);
  add_calibrate_pan_tilt(cmd, exit_code);
}

}  // namespace rangefit::cli
