#pragma once
// What the `rangefit calibrate` subcommands share (calibrate_command.cpp): the options every
// kind takes, the start values from the configuration, and writing the result for review. The
// result is never applied: a TOML fragment with the fields of the configuration it replaces,
// beside the configuration unless --out says where, with a report of residuals and
// uncertainties next to it (FILE.report.txt).

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "calib/raw_sweep_text.hpp"
#include "detect/common/angles.hpp"
#include "fusion/config.hpp"

namespace rangefit::cli::calibrate {

struct CommonArgs {
  std::vector<std::string> scans;
  std::string config, out;
  std::uint64_t seed = 1;
};

// --scans (described by `scans_help`), --config, --out, --seed.
void add_common(CLI::App* cmd, CommonArgs& a, const std::string& scans_help);
std::string read_text(const std::string& path);
std::string vec(const Eigen::Vector3d& v);  // "[x, y, z]", TOML array
// The configuration's [fusion] table, or the defaults without --config.
fusion::FusionConfig start_config(const CommonArgs& a);
// --out, else `name` beside the configuration (or here without one).
std::filesystem::path out_path(const CommonArgs& a, const std::string& name);
// Writes the fragment and its report, prints the report and where both went.
void write_result(const std::filesystem::path& out, const std::string& toml,
                  const std::string& report);
calib::RawSweep load_sweep(const std::string& path, calib::SweepKind kind);
// X,Y,Z,ROLL,PITCH,YAW (mm, rad; R = Rz Ry Rx) as given on the command line.
Eigen::Isometry3d pose_of(const std::vector<double>& v);
// Runs `run` as the subcommand's callback: its exit code, or bad input on an exception.
void on_run(CLI::App* cmd, int* exit_code, std::function<int()> run);
// --cube EDGE,BAR and --cube-pose X,Y,Z,ROLL,PITCH,YAW (required).
void add_cube_options(CLI::App* cmd, std::vector<double>& cube, std::vector<double>& pose,
                      const std::string& frame);

// The css and pantilt subcommands of `calibrate` (calibrate_css.cpp, calibrate_pan_tilt.cpp).
void add_calibrate_css(CLI::App* calibrate, int* exit_code);
void add_calibrate_pan_tilt(CLI::App* calibrate, int* exit_code);

}  // namespace rangefit::cli::calibrate
