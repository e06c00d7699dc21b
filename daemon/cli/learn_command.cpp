// `rangefit learn`: teach an object model from scans of the object alone on the table (thesis
// ch. 6, "show the object once"): the plane is removed, the object segmented and one (or two)
// tapered superquadrics fitted (detect/model_learning.hpp); the model file it writes is what
// `rangefit object --model` and the service's [[objects]] read.
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "daemon/cli/cli_options.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/service/learn_request.hpp"
#include "detect/learn/model_learning.hpp"
#include "io/cloud_io.hpp"
#include "io/object_model_file.hpp"

namespace rangefit::cli {
namespace {

struct LearnArgs {
  std::vector<std::string> clouds;
  int parts = 1;
  std::uint64_t seed = 1;
  std::string out;
  std::string name;
  bool json = false;
};

// The model file's header: where it came from and how well the scan supported it.
std::string provenance(const LearnArgs& a, const LearnResult& r) {
  std::string source = "`rangefit learn` from";
  for (const std::string& f : a.clouds) source += " " + f;
  return daemon::learn_provenance(source, a.seed, r);
}

void print_text(const LearnResult& r) {
  std::cout << r.model.name << ": " << to_string(r.reason) << ", " << r.segment.object.size()
            << " object points, " << r.starts << " starts, " << r.total_ms << " ms\n";
  for (const LearntPart& p : r.parts) {
    const Eigen::Vector3d c = p.T_world_part.translation(), z = p.T_world_part.linear().col(2);
    std::cout << "  " << p.name << ": size " << p.shape.a1 << " " << p.shape.a2 << " " << p.shape.a3
              << " mm, shape " << p.shape.eps1 << " " << p.shape.eps2 << ", taper " << p.shape.kx
              << " " << p.shape.ky << ", centre " << c.x() << " " << c.y() << " " << c.z()
              << ", z-axis " << z.x() << " " << z.y() << " " << z.z() << ", residual "
              << p.residual_mm << " mm, visible " << p.visible_share << "\n";
  }
  for (const PartLink& l : r.model.links) {
    std::cout << "  link " << r.model.parts[l.first].name << "-" << r.model.parts[l.second].name
              << ": angle " << l.angle_rad * 180.0 / std::numbers::pi << " deg, distance "
              << l.distance_mm << " mm";
    if (l.bearing_rad) {
      std::cout << ", bearings " << (*l.bearing_rad)[0] * 180.0 / std::numbers::pi << " "
                << (*l.bearing_rad)[1] * 180.0 / std::numbers::pi << " deg";
    }
    std::cout << "\n";
  }
}

int run(const LearnArgs& a) {
  // Several views in one world frame are fused by taking all their points.
  std::vector<Eigen::Vector3d> points;
  try {
    for (const std::string& f : a.clouds) {
      const PointCloud c = io::read_cloud(f);
      points.insert(points.end(), c.points.begin(), c.points.end());
    }
  } catch (const std::exception& e) {
    std::cerr << "rangefit learn: " << e.what() << "\n";
    return kExitBadInput;
  }
  LearnOptions o;
  o.parts = a.parts;
  o.seed = a.seed;
  o.name = !a.name.empty()                    ? a.name
           : (!a.out.empty() && a.out != "-") ? std::filesystem::path(a.out).stem().string()
                                              : "learnt";
  const LearnResult r = learn_model(points, o);
  if (r.reason == LearnReason::kInvalidOptions || r.reason == LearnReason::kNonFinitePoints ||
      r.reason == LearnReason::kAllAtOnePoint || r.reason == LearnReason::kCollinear) {
    std::cerr << "rangefit learn: " << to_string(r.reason) << "\n";
    return kExitBadInput;
  }
  // The model goes to --out; with --out - and --json both on stdout, the JSON goes to stderr.
  std::ostream& report = (a.out == "-") ? std::cerr : std::cout;
  if (a.json) {
    report << daemon::learn_json(r, points.size(), a.clouds.size()).dump(2) << "\n";
  } else if (a.out != "-") {
    print_text(r);
  }
  if (!r.learnt()) return kExitNotFound;
  if (!a.out.empty()) {
    try {
      io::write_object_model(a.out, r.model, provenance(a, r));
    } catch (const std::exception& e) {
      std::cerr << "rangefit learn: " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  return kExitOk;
}

}  // namespace

void add_learn_command(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<LearnArgs>();
  CLI::App* cmd = app.add_subcommand(
      "learn",
      "Learn an object model (tapered superquadrics) from scans of the object alone on a table "
      "(thesis ch. 6).");
  cmd->add_option("--cloud", args->clouds,
                  "scan of the object (PLY or PCD), mm; give it again for more views in the same "
                  "world frame, which are fused; - reads stdin")
      ->required()
      ->check(cloud_input())
      ->take_all();
  cmd->add_option("--parts", args->parts, "parts of the model: 1, or 2 (e.g. head and shaft)")
      ->check(CLI::Range(1, 2));
  cmd->add_option("--seed", args->seed, "random seed (the result depends only on it)");
  cmd->add_option("--out", args->out, "write the model file (TOML) here; - for stdout");
  cmd->add_option("--name", args->name, "the model's name (default: --out's file name)");
  cmd->add_flag("--json", args->json, "print the result as JSON");
  cmd->callback([args, exit_code] { *exit_code = run(*args); });
}

}  // namespace rangefit::cli
