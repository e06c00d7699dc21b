#include "daemon/cli/bore_command.hpp"

#include <cmath>
#include <exception>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "daemon/cli/cli_options.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "daemon/cli/png_output.hpp"
#include "daemon/service/bore_fit_json.hpp"
#include "daemon/service/bore_shape_json.hpp"
#include "daemon/service/detection_adapter.hpp"
#include "daemon/service/json_codec.hpp"
#include "detect/bore/bore_detector.hpp"
#include "io/cloud_io.hpp"

namespace rangefit::cli {
namespace {

using daemon::json_vec;

struct BoreArgs {
  std::string cloud;
  std::string entrance, axis, plane_normal, view_dir, sensor_position, major_axis;
  double radius = 0.0;
  double outer_radius = 0.0;
  double half_angle = 0.0, cylinder_radius = 0.0, radius2 = 0.0;  // rad, mm, mm
  std::string walls = "inner";
  double normal_keep = 1.0;
  std::uint64_t seed = 1;
  bool json = false;
  std::string png;
};

// "X,Y,Z" -> vector; nullopt on anything else (wrong count, not a number, NaN/Inf, beyond
// kMaxCoordinateMm).
std::optional<Eigen::Vector3d> parse_vec(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      const double x = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(x) || std::abs(x) > kMaxCoordinateMm)
        return std::nullopt;
      v.push_back(x);
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }
  if (v.size() != 3) return std::nullopt;
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

nlohmann::json to_json(const BoreResult& r) {
  nlohmann::json j;
  j["found"] = r.found;
  if (r.found) {
    j["model"] = "cylinder";
    j["entrance"] = json_vec(r.entrance);
    j["axis"] = json_vec(r.axis);
    j["radius"] = r.radius;
    // A cone's or ellipse's "sigma" is its shape's; a cylinder's is its refinement's.
    j.update(daemon::bore_fit_json(r));
    if (r.shape) j.update(daemon::bore_shape_json(*r.shape));
    j["rsf_radius"] = r.rsf_radius;
  } else {
    j["reason"] = std::string(to_string(r.reason));
  }
  if (r.outer) {
    nlohmann::json o;
    o["found"] = r.outer->found;
    if (r.outer->found) {
      o["entrance"] = json_vec(r.outer->entrance);
      o["axis"] = json_vec(r.outer->axis);
      o["radius"] = r.outer->radius;
      o["refined"] = r.outer->refined;
    } else {
      o["reason"] = std::string(to_string(r.outer->reason));
    }
    o["wall_points"] = r.outer->wall;
    j["outer"] = o;
  }
  const BoreCounts& c = r.counts;
  j["points"] = {{"input", c.input},
                 {"non_finite", c.non_finite},
                 {"roi", c.roi},
                 {"normal_queries", c.normal_queries},
                 {"normals", c.normals},
                 {"plane", c.plane},
                 {"wall", c.wall},
                 {"wall_final", c.wall_final},
                 {"refine_inliers", c.refine_inliers}};
  const BoreTimes& t = r.time_ms;
  j["time_ms"] = {{"roi", t.roi},    {"normals", t.normals}, {"segmentation", t.segmentation},
                  {"rsf", t.rsf},    {"refine", t.refine},   {"entrance", t.entrance},
                  {"total", t.total}};
  return j;
}

std::string vec_text(const Eigen::Vector3d& x) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(4) << x.x() << ", " << x.y() << ", " << x.z();
  return s.str();
}

void print_shape(const BoreResult& r) {
  if (!r.shape) return;
  const BoreShape& s = *r.shape;
  constexpr double kDeg = 180.0 / std::numbers::pi;
  if (s.cone) {
    std::cout << "  cone      half-angle " << s.half_angle << " rad (" << s.half_angle * kDeg
              << " deg, +- " << s.sigma_half_angle * kDeg << ")\n";
    if (s.cylinder_radius > 0.0) {
      std::cout << "  cylinder  radius " << s.cylinder_radius << " mm below the cone\n";
    }
  } else {
    std::cout << "  ellipse   radius2 " << s.radius2 << " mm, major axis " << vec_text(s.major_axis)
              << "\n";
  }
}

void print_text(const BoreResult& r) {
  std::cout << std::fixed << std::setprecision(4);
  if (!r.found) {
    std::cout << "bore not found: " << to_string(r.reason) << " (" << r.counts.roi
              << " points in the region, " << r.counts.wall << " wall points)\n";
    return;
  }
  const auto v = vec_text;
  std::cout << "bore found\n"
            << "  entrance  " << v(r.entrance) << " mm\n"
            << "  axis      " << v(r.axis) << " (unit, out of the bore)\n"
            << "  radius    " << r.radius << " mm"
            << (!r.shape        ? "\n"
                : r.shape->cone ? " (the cone's, at the entrance)\n"
                                : " (along the major axis)\n");
  print_shape(r);
  if (!r.shape && r.refined && r.sigma_radius > 0.0) {
    std::cout << "  sigma     axis " << r.sigma_axis * 180.0 / std::numbers::pi << " deg, offset "
              << r.sigma_offset << " mm, radius " << r.sigma_radius << " mm (one sigma)\n";
  }
  std::cout << "  points    " << r.counts.roi << " in region, " << r.counts.plane << " plane, "
            << r.counts.wall << " wall" << (r.second_fit ? " (notch re-fit ran)" : "") << "\n"
            << std::setprecision(2) << "  time      " << r.time_ms.total << " ms\n";
  if (r.outer) {
    if (r.outer->found) {
      std::cout << std::setprecision(4) << "outer wall found\n"
                << "  entrance  " << v(r.outer->entrance) << " mm\n"
                << "  axis      " << v(r.outer->axis) << "\n"
                << "  radius    " << r.outer->radius << " mm\n";
    } else {
      std::cout << "outer wall not found: " << to_string(r.outer->reason) << "\n";
    }
  }
}

int run(const BoreArgs& a) {
  const auto entrance = parse_vec(a.entrance);
  const auto axis = parse_vec(a.axis);
  if (!entrance || !axis || axis->norm() == 0.0) {
    std::cerr << "rangefit bore: --cad-entrance and --cad-axis need three finite numbers X,Y,Z "
                 "within +-1e6 (axis non-zero)\n";
    return kExitBadInput;
  }
  if (!std::isfinite(a.radius) || a.radius <= 0.0) {
    std::cerr << "rangefit bore: --cad-radius must be a positive number of millimetres\n";
    return kExitBadInput;
  }
  if (a.walls == "both" && !(a.outer_radius > a.radius)) {
    std::cerr << "rangefit bore: --walls both needs --cad-outer-radius larger than --cad-radius\n";
    return kExitBadInput;
  }
  daemon::BoreQuery query;
  query.entrance = *entrance;
  query.axis = *axis;
  query.radius = a.radius;
  query.seed = a.seed;
  query.normal_keep = a.normal_keep;
  query.outer_radius = a.outer_radius;
  if (a.walls == "outer") query.walls = BoreWalls::kOuter;
  if (a.walls == "both") query.walls = BoreWalls::kBoth;
  query.half_angle = a.half_angle;
  query.cylinder_radius = a.cylinder_radius;
  query.radius2 = a.radius2;
  daemon::ScanSensor sensor;  // what the user knows of the sensor
  const std::pair<const std::string*, const char*> optional_vectors[] = {
      {&a.plane_normal, "--cad-plane-normal"},
      {&a.view_dir, "--view-dir"},
      {&a.sensor_position, "--sensor-position"},
      {&a.major_axis, "--cad-major-axis"}};
  for (const auto& [text, name] : optional_vectors) {
    if (text->empty()) continue;
    const auto v = parse_vec(*text);
    if (!v || (text != &a.sensor_position && v->norm() == 0.0)) {
      std::cerr << "rangefit bore: " << name << " needs three finite numbers X,Y,Z within +-1e6\n";
      return kExitBadInput;
    }
    if (text == &a.plane_normal) query.plane_normal = *v;
    if (text == &a.view_dir) sensor.view_dir = *v;
    if (text == &a.sensor_position) sensor.sensor_position = *v;
    if (text == &a.major_axis) query.major_axis = *v;
  }
  if (a.radius2 > 0.0 && !query.major_axis) {
    std::cerr << "rangefit bore: --cad-radius2 needs --cad-major-axis\n";
    return kExitBadInput;
  }
  PointCloud cloud;
  try {
    cloud = io::read_cloud(a.cloud);
  } catch (const std::exception& e) {
    std::cerr << "rangefit bore: " << e.what() << "\n";
    return kExitBadInput;
  }
  const daemon::BoreDetection d = daemon::bore_detection(query, sensor);
  const BoreResult r = detect_bore(cloud, d.prior, d.options);
  if (a.json) {
    std::cout << to_json(r).dump() << "\n";
  } else {
    print_text(r);
  }
  if (!write_png_if_asked(a.png, cloud, r, d.options)) return kExitBadInput;
  if (r.found) return kExitOk;
  const bool bad = r.reason == BoreReason::kBadPrior || r.reason == BoreReason::kBadShape;
  return bad ? kExitBadInput : kExitNotFound;
}

}  // namespace

void add_bore_command(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<BoreArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bore",
      "Find a bore hole in a scan from its CAD prior (thesis ch. 4) and print entrance, axis "
      "and radius. Units: mm. Exit 0 found, 2 not found, 1 bad input.");
  cmd->add_option("--cloud", args->cloud, "Scan file, .ply or .pcd (points in mm); - reads stdin")
      ->required()
      ->check(cloud_input());
  cmd->add_option("--cad-entrance", args->entrance,
                  "Expected bore entrance X,Y,Z in the scan's frame, mm")
      ->required();
  cmd->add_option("--cad-axis", args->axis, "Expected bore axis X,Y,Z (any length, either sign)")
      ->required();
  cmd->add_option("--cad-radius", args->radius, "Expected bore radius, mm")
      ->required()
      ->check(finite_range(1e-3, 1e5));
  cmd->add_option("--cad-outer-radius", args->outer_radius,
                  "A thick-walled pipe's outer wall radius, mm (the bore is its inner wall)")
      ->check(finite_range(1e-3, 1e5));
  cmd->add_option("--cad-half-angle", args->half_angle,
                  "A conical bore: the cone's half-angle, rad (a 90 deg countersink: 0.7854), "
                  "narrowing with depth from --cad-radius at the entrance")
      ->check(finite_range(0.0, 1.39));
  cmd->add_option("--cad-cylinder-radius", args->cylinder_radius,
                  "With --cad-half-angle: the radius of the cylindrical bore the cone ends in "
                  "(a countersunk hole), mm")
      ->check(finite_range(1e-3, 1e5));
  cmd->add_option("--cad-radius2", args->radius2,
                  "An elliptic bore: the semi-axis across --cad-major-axis, mm (--cad-radius is "
                  "the one along it)")
      ->check(finite_range(1e-3, 1e5));
  cmd->add_option("--cad-major-axis", args->major_axis,
                  "An elliptic bore: direction X,Y,Z of the --cad-radius semi-axis (across the "
                  "bore axis)");
  cmd->add_option("--walls", args->walls,
                  "Which wall of a pipe to fit: inner (the bore, default), outer "
                  "(--cad-outer-radius, else --cad-radius) or both (the outer one as \"outer\")")
      ->check(CLI::IsMember({"inner", "outer", "both"}));
  cmd->add_option("--cad-plane-normal", args->plane_normal,
                  "Normal X,Y,Z of the surface around the bore (default: the axis)");
  cmd->add_option("--view-dir", args->view_dir,
                  "Direction X,Y,Z from the part toward the sensor (default: the plane normal)");
  cmd->add_option("--sensor-position", args->sensor_position,
                  "Sensor position X,Y,Z in mm, instead of --view-dir");
  cmd->add_option("--normal-keep", args->normal_keep,
                  "Share (0..1] of region points that get a normal (thesis: 0.2)")
      ->check(finite_range(0.001, 1.0));
  cmd->add_option("--seed", args->seed, "Seed of the random sampling (same seed, same result)");
  cmd->add_flag("--json", args->json,
                "Print one JSON object: found, model, entrance, axis, radius (a cone: "
                "half_angle, cylinder_radius; an ellipse: radius2, major_axis; their sigma), "
                "plane_normal, refined, second_fit, a refined cylinder's sigma (axis_rad, "
                "offset_mm, radius_mm: one-sigma errors of the fit), reason, points, time_ms");
  cmd->add_option("--png", args->png,
                  "Also draw the scan and the fitted bore to this PNG (as `rangefit render`)");
  cmd->callback([args, exit_code] { *exit_code = run(*args); });
}

}  // namespace rangefit::cli
