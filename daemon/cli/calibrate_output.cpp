#include "daemon/cli/calibrate_output.hpp"

#include <Eigen/Geometry>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "hal/rpy.hpp"

namespace rangefit::cli::calibrate {

namespace fs = std::filesystem;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(10);
  s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return s.str();
}

fusion::FusionConfig start_config(const CommonArgs& a) {
  if (a.config.empty()) return {};
  const fusion::FusionConfigResult r = fusion::load_fusion_config(a.config);
  if (!r.config) throw std::runtime_error(r.error);
  return *r.config;
}

fs::path out_path(const CommonArgs& a, const std::string& name) {
  if (!a.out.empty()) return a.out;
  const fs::path dir = a.config.empty() ? fs::path(".") : fs::path(a.config).parent_path();
  return (dir.empty() ? fs::path(".") : dir) / name;
}

void write_result(const fs::path& out, const std::string& toml, const std::string& report) {
  fs::path report_path = out;
  report_path += ".report.txt";
  std::ofstream(out) << toml;
  std::ofstream(report_path) << report;
  if (!fs::exists(out) || !fs::exists(report_path)) {
    throw std::runtime_error(out.string() + ": cannot write");
  }
  std::cout << report << "written: " << out.string() << " (review it, then include it in the "
            << "configuration; nothing was applied)\nreport: " << report_path.string() << "\n";
}

calib::RawSweep load_sweep(const std::string& path, calib::SweepKind kind) {
  calib::RawSweepParse p = calib::parse_raw_sweep(read_text(path), path);
  if (!p.sweep) throw std::runtime_error(p.error);
  if (p.sweep->kind != kind) throw std::runtime_error(path + ": not a sweep of this kind");
  return std::move(*p.sweep);
}

Eigen::Isometry3d pose_of(const std::vector<double>& v) {
  return hal::pose_xyz_rpy(v[0], v[1], v[2], v[3], v[4], v[5]);
}

void add_common(CLI::App* cmd, CommonArgs& a, const std::string& scans_help) {
  cmd->add_option("--scans", a.scans, scans_help)->required()->check(CLI::ExistingFile);
  cmd->add_option("--config", a.config,
                  "configuration with the [fusion] start values (default: built-in defaults)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", a.out, "result TOML (default: beside --config)");
  cmd->add_option("--seed", a.seed, "RANSAC seed");
}

void add_cube_options(CLI::App* cmd, std::vector<double>& cube, std::vector<double>& pose,
                      const std::string& frame) {
  cmd->add_option("--cube", cube, "cube EDGE,BAR (mm)")
      ->expected(2)
      ->delimiter(',')
      ->check(finite_range(1.0, kMaxCoordinateMm));
  cmd->add_option("--cube-pose", pose,
                  "cube pose in the " + frame + " frame X,Y,Z,ROLL,PITCH,YAW (mm, rad)")
      ->required()
      ->expected(6)
      ->delimiter(',')
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
}

void on_run(CLI::App* cmd, int* exit_code, std::function<int()> run) {
  cmd->callback([exit_code, run] {
    try {
      *exit_code = run();
    } catch (const std::exception& e) {
      std::cerr << "rangefit calibrate: " << e.what() << "\n";
      *exit_code = kExitBadInput;
    }
  });
}

}  // namespace rangefit::cli::calibrate
