// `rangefit calibrate stripe|css|pantilt`: the cell's extrinsics from raw scans of a reference
// body (calib/). The result is never applied: it is written as a TOML fragment with the fields
// of the configuration it replaces, beside the configuration unless --out says where, with a
// report of residuals and uncertainties next to it; the operator reviews it and includes it.
#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "calib/raw_sweep_text.hpp"
#include "calib/stripe_calibration.hpp"
#include "daemon/cli/cli_options.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "fusion/config.hpp"

namespace rangefit::cli {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct CommonArgs {
  std::vector<std::string> scans;
  std::string config, out;
  std::uint64_t seed = 1;
};

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

// The start values: the configuration's [fusion] table, or the defaults without --config.
fusion::FusionConfig start_config(const CommonArgs& a) {
  if (a.config.empty()) return {};
  const fusion::FusionConfigResult r = fusion::load_fusion_config(a.config);
  if (!r.config) throw std::runtime_error(r.error);
  return *r.config;
}

// --out, else beside the configuration (or here without one).
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
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return T;
}

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

void add_common(CLI::App* cmd, CommonArgs& a) {
  cmd->add_option("--scans", a.scans, "raw scan file(s) (calib/raw_sweep_text.hpp)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--config", a.config,
                  "configuration with the [fusion] start values (default: built-in defaults)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", a.out, "result TOML (default: beside --config)");
  cmd->add_option("--seed", a.seed, "RANSAC seed");
}

template <class Run>
void on_run(CLI::App* cmd, int* exit_code, Run run) {
  cmd->callback([exit_code, run] {
    try {
      *exit_code = run();
    } catch (const std::exception& e) {
      std::cerr << "rangefit calibrate: " << e.what() << "\n";
      *exit_code = kExitBadInput;
    }
  });
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
    add_common(s, a->common);
    s->add_option("--cube", a->cube, "cube EDGE,BAR (mm)")
        ->expected(2)
        ->delimiter(',')
        ->check(finite_range(1.0, kMaxCoordinateMm));
    s->add_option("--cube-pose", a->pose, "cube pose on the table X,Y,Z,ROLL,PITCH,YAW (mm, rad)")
        ->required()
        ->expected(6)
        ->delimiter(',')
        ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
    on_run(s, exit_code, [a] { return run_stripe(a->common, a->cube, a->pose); });
  }
}

}  // namespace rangefit::cli
