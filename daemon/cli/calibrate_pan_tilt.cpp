// `rangefit calibrate pantilt`: t_s, t_w and the encoder zeros of the mobile scanning head
// (eq. 5.7, calib/pan_tilt_calibration.hpp) from pan sweeps over the calibration cube at two or
// more tilt angles, one raw sweep file each. Writes the [fusion.pan_tilt] fields.
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "calib/pan_tilt_calibration.hpp"
#include "daemon/cli/calibrate_output.hpp"
#include "daemon/cli/commands.hpp"

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
  const hal::PanTiltGeometry& g = r.geometry;
  std::ostringstream toml, rep;
  toml.precision(12);
  toml << "# rangefit calibrate pantilt, from " << sweeps.size()
       << " sweeps; see the .report.txt beside it\n"
       << "[fusion.pan_tilt]\n"
       << "t_s_mm = " << vec(g.t_s_mm) << "\n"
       << "t_w_mm = " << vec(g.t_w_mm) << "\n"
       << "pan_zero_rad = " << g.pan_zero_rad << "\n"
       << "tilt_zero_rad = " << g.tilt_zero_rad << "\n";
  rep.precision(5);
  rep << "pan-tilt head calibration (eq. 5.7), " << sweeps.size() << " sweeps\n";
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    rep << "  round " << i + 1 << ": " << r.rounds[i].plane_points << " plane points, rms "
        << r.rounds[i].rms_mm << " mm\n";
  }
  rep << "  plane rms " << r.initial_rms_mm << " -> " << r.rms_mm << " mm in " << r.lm_iterations
      << " iterations\n"
      << "  t_s " << vec(g.t_s_mm) << " mm (was " << vec(start.t_s_mm) << "), 1 sigma "
      << vec(r.t_s_sigma_mm) << " mm\n"
      << "  t_w " << vec(g.t_w_mm) << " mm (was " << vec(start.t_w_mm) << "), 1 sigma "
      << vec(r.t_w_sigma_mm) << " mm\n"
      << "  pan zero " << g.pan_zero_rad << " rad (was " << start.pan_zero_rad << "), 1 sigma "
      << r.zero_sigma_rad.x() / kDeg << " deg\n"
      << "  tilt zero " << g.tilt_zero_rad << " rad (was " << start.tilt_zero_rad << "), 1 sigma "
      << r.zero_sigma_rad.y() / kDeg << " deg\n";
  write_result(out_path(a, "calibration_pantilt.toml"), toml.str(), rep.str());
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
