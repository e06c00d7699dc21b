// `rangefit calibrate pantilt`: t_s, t_w and the encoder zeros of the mobile scanning head
// (eq. 5.7, calib/pan_tilt_calibration.hpp) from pan sweeps over the calibration cube at two or
// more tilt angles, one raw sweep file each. Writes the [fusion.pan_tilt] fields.
#include <iostream>
#include <memory>
#include <stdexcept>

#include "calib/pan_tilt_calibration.hpp"
#include "daemon/cli/calibrate_output.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/service/calibrate_pan_tilt_request.hpp"

namespace rangefit::cli::calibrate {
namespace {

int run_pan_tilt(const CommonArgs& a, const std::vector<double>& cube,
                 const std::vector<double>& pose) {
  std::vector<calib::RawSweep> sweeps;
  for (const std::string& path : a.scans) {
    sweeps.push_back(load_sweep(path, calib::SweepKind::kPanTilt));
  }
  const fusion::FusionConfig config = start_config(a);
  const hal::PanTiltGeometry& start = config.pan_tilt.geometry;
  calib::PanTiltCalibrationInput in;
  for (const calib::RawSweep& s : sweeps) in.sweeps.push_back({s.profiles, s.angles});
  in.cube = {cube[0], cube[1]};
  in.T_world_cube = pose_of(pose);
  calib::PanTiltCalibrationOptions options;
  options.planes.seed = a.seed;
  const calib::PanTiltCalibrationResult r = calib::calibrate_pan_tilt(in, start, options);
  if (!r.ok) {
    std::cerr << "rangefit calibrate pantilt: " << r.reason << "\n";
    return kExitNotFound;
  }
  const std::string source = "rangefit calibrate pantilt";
  write_result(out_path(a, "calibration_pantilt.toml"),
               daemon::pan_tilt_calibration_toml(r, sweeps.size(), source),
               daemon::pan_tilt_calibration_report(r, start, sweeps.size(), source));
  return kExitOk;
}

}  // namespace

void add_calibrate_pan_tilt(CLI::App* calibrate, int* exit_code) {
  auto* s = calibrate->add_subcommand(
      "pantilt",
      "pan-tilt head t_s, t_w and encoder zeros from pan sweeps over the calibration cube at two "
      "or more tilts (one --scans file each)");
  struct Args {
    CommonArgs common;
    std::vector<double> cube{120.0, 12.0}, pose;
  };
  auto a = std::make_shared<Args>();
  add_common(s, a->common, "raw pan-tilt sweeps, one per tilt (calib/raw_sweep_text.hpp)");
  add_cube_options(s, a->cube, a->pose, "head's world");
  on_run(s, exit_code, [a] { return run_pan_tilt(a->common, a->cube, a->pose); });
}

}  // namespace rangefit::cli::calibrate
