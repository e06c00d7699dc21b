#include "daemon/cli/render_command.hpp"

#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "daemon/cli/commands.hpp"
#include "daemon/service/bore_shape_json.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/object_result_json.hpp"
#include "daemon/service/result_picture.hpp"
#include "io/cloud_io.hpp"
#include "io/object_model_file.hpp"
#include "render/legend_text.hpp"
#include "render/render.hpp"

namespace rangefit::cli {
namespace {

struct RenderArgs {
  std::string cloud, result, model, out;
  std::string colour;  // empty: by distance when a model is drawn, else by height
  std::vector<double> view_dir, sensor_position;
  bool whole_scan = false;
  int panel_width = 560, panel_height = 480;
};

Eigen::Vector3d vec(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

using render::legend_format;
using render::legend_vector;

// The shape of part `name` in the model file; throws when there is none to draw.
Superquadric shape_of(const std::optional<ObjectModel>& model, const std::string& name) {
  if (!model) {
    throw std::invalid_argument(
        "the result has object parts; --model MODEL.toml gives their shape");
  }
  for (const ModelPart& p : model->parts) {
    if (p.name == name) return p.shape;
  }
  throw std::invalid_argument("part \"" + name + "\" is not in the model " + model->name);
}

// `rangefit bore --json`: the same fields as BoreResult, so the same legend.
render::Drawing bore_json(const nlohmann::json& j) {
  BoreResult r;
  r.found = j.at("found").get<bool>();
  if (r.found) {
    r.entrance = vec(j.at("entrance"));
    r.axis = vec(j.at("axis")).normalized();
    r.radius = j.at("radius").get<double>();
    r.plane_normal = vec(j.value("plane_normal", nlohmann::json::array({0.0, 0.0, 0.0})));
    if (r.plane_normal.norm() == 0.0) r.plane_normal = r.axis;
    r.rsf_radius = j.value("rsf_radius", r.radius);
    r.second_fit = j.value("second_fit", false);
    r.refined = j.value("refined", false);
    r.shape = daemon::bore_shape_from_json(j);
  }
  const nlohmann::json points = j.value("points", nlohmann::json::object());
  r.counts.roi = points.value("roi", std::size_t{0});
  r.counts.plane = points.value("plane", std::size_t{0});
  r.counts.wall = points.value("wall", std::size_t{0});
  r.counts.wall_final = points.value("wall_final", std::size_t{0});
  r.time_ms.total = j.value("time_ms", nlohmann::json::object()).value("total", 0.0);
  render::Drawing d = render::bore_drawing(r);
  if (!r.found) d.legend.front() = "bore not found: " + j.value("reason", std::string("?"));
  return d;
}

// `rangefit object --json`: every part of every instance.
render::Drawing object_json(const nlohmann::json& j, const std::optional<ObjectModel>& model) {
  render::Drawing d;
  d.legend.push_back(
      j.at("object").get<std::string>() +
      (j.at("found").get<bool>() ? ": found"
                                 : ": not found (" + j.value("reason", std::string()) + ")") +
      legend_format(", %d hypotheses, %.1f ms", j.value("hypotheses_evaluated", 0),
                    j.value("time_ms", nlohmann::json::object()).value("total", 0.0)));
  const nlohmann::json instances = j.value("instances", nlohmann::json::array());
  for (std::size_t i = 0; i < instances.size(); ++i) {
    for (const nlohmann::json& p : instances[i].at("parts")) {
      const auto& q = p.at("quaternion");
      render::DrawnPart part;
      part.name = p.at("name").get<std::string>();
      part.shape = shape_of(model, part.name);
      part.T_world_part.linear() = Eigen::Quaterniond(q.at(0).get<double>(), q.at(1).get<double>(),
                                                      q.at(2).get<double>(), q.at(3).get<double>())
                                       .normalized()
                                       .toRotationMatrix();
      part.T_world_part.translation() = vec(p.at("center"));
      d.parts.push_back(part);
      const nlohmann::json s = p.value("scores", nlohmann::json::object());
      d.legend.push_back(legend_format("[%zu] ", i) + part.name + "  centre " +
                         legend_vector(part.T_world_part.translation()) + " mm, z-axis " +
                         legend_vector(part.T_world_part.linear().col(2)));
      d.legend.push_back(render::scores_line(daemon::part_scores_from_json(s)));
    }
  }
  return d;
}

// rangefitd's result.json of a spool entry: poses and one score per part, drawn as the service
// draws its own picture of it.
render::Drawing spool_json(const nlohmann::json& j, const std::optional<ObjectModel>& model) {
  daemon::DetectionResult r;
  std::string error;
  if (!daemon::from_json(j, r, &error)) throw std::invalid_argument(error);
  if (r.kind == daemon::DetectKind::kObject && !r.parts.empty() && !model) {
    throw std::invalid_argument(
        "the result has object parts; --model MODEL.toml gives their shape");
  }
  return daemon::result_drawing(r, model ? &*model : nullptr);
}

render::Drawing drawing_from(const nlohmann::json& j, const std::optional<ObjectModel>& model) {
  if (!j.is_object()) throw std::invalid_argument("the result is not a JSON object");
  if (j.contains("request_id")) return spool_json(j, model);
  if (j.contains("object")) return object_json(j, model);
  if (j.contains("found")) return bore_json(j);
  throw std::invalid_argument(
      "not a result of `rangefit bore|object --json` nor a spool entry's result.json");
}

int run(const RenderArgs& a) {
  PointCloud cloud;
  render::Drawing drawing;
  try {
    cloud = io::read_cloud(a.cloud);
    std::optional<ObjectModel> model;
    if (!a.model.empty()) model = io::read_object_model(a.model);
    if (!a.result.empty()) {
      std::ifstream in(a.result);
      if (!in) throw std::runtime_error(a.result + ": cannot open");
      drawing = drawing_from(nlohmann::json::parse(in), model);
    }
  } catch (const std::exception& e) {
    std::cerr << "rangefit render: " << e.what() << "\n";
    return kExitBadInput;
  }
  render::RenderOptions o;
  o.panel_width = a.panel_width;
  o.panel_height = a.panel_height;
  o.zoom_to_models = !a.whole_scan;
  const bool distance = a.colour.empty() ? !drawing.empty() : a.colour == "distance";
  o.colouring = distance ? render::Colouring::kModelDistance : render::Colouring::kHeight;
  if (a.view_dir.size() == 3) o.toward_sensor = Eigen::Vector3d(a.view_dir.data());
  if (a.sensor_position.size() == 3) o.sensor_position = Eigen::Vector3d(a.sensor_position.data());
  std::string error;
  const bool ok = render::write_detection_png(a.out, cloud, drawing, o, &error);
  render::release_font_caches();  // the command draws one picture
  if (!ok) {
    std::cerr << "rangefit render: " << error << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Draw a scan, and the detection of a result JSON over it, as a PNG: the scan from the "
      "sensor and from above, the fitted bore or parts as wireframes, and a legend.");
  cmd->add_option("--cloud", args->cloud, "Scan file, .ply or .pcd (points in mm)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--result", args->result,
                  "Result JSON: what `rangefit bore|object --json` prints, or a spool entry's "
                  "result.json")
      ->check(CLI::ExistingFile);
  cmd->add_option("--model", args->model, "Object model file (TOML) of an object result's parts")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "PNG file to write")->required();
  cmd->add_option("--colour", args->colour,
                  "Point colours: height (z) or distance (to the model); default distance when "
                  "a model is drawn")
      ->check(CLI::IsMember({"height", "distance"}));
  cmd->add_option("--view-dir", args->view_dir,
                  "Direction x y z from the scene toward the sensor, for the left picture "
                  "(default: along the bore axis, or obliquely from above)")
      ->expected(3);
  cmd->add_option("--sensor-position", args->sensor_position, "Sensor position x y z, mm")
      ->expected(3);
  cmd->add_flag("--whole-scan", args->whole_scan,
                "Frame the whole scan instead of the models and their surroundings");
  cmd->add_option("--panel-width", args->panel_width, "Width of each of the two pictures, px")
      ->check(CLI::Range(64, 4096));
  cmd->add_option("--panel-height", args->panel_height, "Height of the pictures, px")
      ->check(CLI::Range(64, 4096));
  cmd->callback([args, exit_code] { *exit_code = run(*args); });
}

}  // namespace rangefit::cli
