#include "daemon/cli/object_command.hpp"

#include <exception>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "daemon/cli/cli_options.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/option_checks.hpp"
#include "daemon/cli/png_output.hpp"
#include "daemon/service/detection_adapter.hpp"
#include "daemon/service/object_result_json.hpp"
#include "detect/object/object_detector.hpp"
#include "io/cloud_io.hpp"
#include "io/object_model_file.hpp"

namespace rangefit::cli {
namespace {

struct ObjectArgs {
  std::vector<std::string> clouds;  // one scan, or the two cameras' of one laser plane
  std::string model;
  int hypotheses = 0;  // 0: the detector's defaults (32 with early stop, 12 per compound part)
  int trials = 10;
  int instances = 1;
  std::uint64_t seed = 1;
  std::vector<double> viewpoint;
  bool json = false;
  std::string png;
};

// The service's result details (object_result_json), with the verdict and the best instance's
// parts at the top level.
nlohmann::json to_json(const ObjectModel& model, const ObjectDetectResult& r) {
  nlohmann::json j;
  j["object"] = model.name;
  j["found"] = r.found();
  j["reason"] = to_string(r.reason);
  j.update(daemon::object_result_json(model, r));
  j["parts"] = r.instances.empty() ? nlohmann::json::array() : j["instances"][0]["parts"];
  return j;
}

void print_text(const ObjectModel& model, const ObjectDetectResult& r) {
  std::cout << model.name << ": " << (r.found() ? "found" : "not found") << " ("
            << to_string(r.reason) << "), " << r.hypotheses_evaluated << " hypotheses, "
            << r.time.total_ms << " ms\n";
  for (const Rejection& x : r.rejections) {
    std::cout << "  rejected " << model.parts[x.part].name << " at " << x.centre.x() << " "
              << x.centre.y() << " " << x.centre.z() << ": " << to_string(x.check) << " " << x.value
              << " (limit " << x.limit << ")\n";
  }
  for (std::size_t i = 0; i < r.instances.size(); ++i) {
    for (const DetectedPart& p : r.instances[i].parts) {
      const Eigen::Vector3d c = p.center(), z = p.z_axis();
      std::cout << "  [" << i << "] " << p.name << " centre " << c.x() << " " << c.y() << " "
                << c.z() << " mm, z-axis " << z.x() << " " << z.y() << " " << z.z() << ", M "
                << p.scores.measure << " I " << p.scores.interior << " S " << p.scores.surface
                << " coverage " << p.scores.coverage << " seen through " << p.scores.seen_through
                << "\n";
    }
  }
}

int run(const ObjectArgs& a) {
  ObjectModel model;
  PointCloud cloud;
  try {
    model = io::read_object_model(a.model);
    if (a.clouds.size() > 2)
      throw std::invalid_argument("--cloud: one scan, or two cameras' scans");
    cloud = io::read_cloud(a.clouds.at(0));
    if (a.clouds.size() == 2) {
      // The second camera's sweep of the same laser plane: its points join the first's, and the
      // view gets its camera, so either camera's sight counts (rangefitd's `sensors`).
      const PointCloud second = io::read_cloud(a.clouds[1]);
      const std::optional<SensorView> both = with_second_camera(cloud.sensor, second.sensor);
      if (!both) {
        throw std::invalid_argument(a.clouds[1] + ": not a second camera of " + a.clouds[0] +
                                    "'s laser sweep (each scan's rangefit sensor line: the same "
                                    "plane, axis and sweep range, one camera each)");
      }
      append_view(cloud, second);
      cloud.sensor = *both;
    }
  } catch (const std::exception& e) {
    std::cerr << "rangefit object: " << e.what() << "\n";
    return kExitBadInput;
  }
  daemon::ObjectQuery query;
  query.hypotheses = a.hypotheses;
  query.trials = a.trials;
  query.instances = a.instances;
  query.seed = a.seed;
  daemon::ScanSensor sensor;  // what the user knows of the sensor
  sensor.view = cloud.sensor;  // a scan saved by rangefit says how it was taken
  if (a.viewpoint.size() == 3)
    sensor.sensor_position = Eigen::Vector3d(a.viewpoint[0], a.viewpoint[1], a.viewpoint[2]);
  const ObjectDetectOptions o = daemon::object_detect_options(query, model, sensor);
  const ObjectDetectResult r = detect_object(model, cloud.points, o);
  if (r.reason == DetectReason::kInvalidModel || r.reason == DetectReason::kInvalidOptions) {
    std::cerr << "rangefit object: " << to_string(r.reason) << "\n";
    return kExitBadInput;
  }
  if (a.json) {
    std::cout << to_json(model, r).dump(2) << "\n";
  } else {
    print_text(model, r);
  }
  if (!write_png_if_asked(a.png, cloud, model, r, o)) return kExitBadInput;
  return r.found() ? kExitOk : kExitNotFound;
}

}  // namespace

void add_object_command(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<ObjectArgs>();
  CLI::App* cmd = app.add_subcommand(
      "object",
      "Find a superquadric object model in a scan, or in the two sweeps of a stripe cell's "
      "cameras on either side of its laser plane (thesis ch. 5).");
  cmd->add_option("--cloud", args->clouds,
                  "scene point cloud (PLY or PCD), mm; - reads stdin. Given twice: the sweeps of "
                  "the two cameras of one laser plane (as saved by rangefit), fused")
      ->required()
      ->check(cloud_input())
      ->take_all();
  cmd->add_option("--model", args->model, "object model file (TOML, see data/models)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--hypotheses", args->hypotheses,
                  "m: pose hypotheses per part (default: up to 32, "
                  "stopping once confirmed; 12 per part of compound models)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--trials", args->trials, "n: RANSAC trials per hypothesis")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--instances", args->instances, "K: instances to report, best first")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--seed", args->seed, "random seed (the result depends only on it)");
  add_vector_option(
      cmd, "--viewpoint", args->viewpoint,
      "sensor position X,Y,Z (or X Y Z), mm (optional; enables the free-space check)")
      ->check(finite_range(-kMaxCoordinateMm, kMaxCoordinateMm));
  cmd->add_flag("--json", args->json, "print the result as JSON");
  cmd->add_option("--png", args->png,
                  "also draw the scan and the found parts to this PNG (as `rangefit render`)");
  cmd->callback([args, exit_code] { *exit_code = run(*args); });
}

}  // namespace rangefit::cli
