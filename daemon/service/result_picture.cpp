#include "daemon/service/result_picture.hpp"

#include <cstdio>
#include <stdexcept>

#include "daemon/service/bore_shape_json.hpp"
#include "daemon/service/object_result_json.hpp"
#include "render/legend_text.hpp"
#include "render/render.hpp"

namespace rangefit::daemon {
namespace {

using render::legend_format;
using render::legend_vector;

Superquadric shape_of(const ObjectModel* model, const std::string& name) {
  if (model == nullptr) {
    throw std::invalid_argument("the result has object parts; their model gives their shape");
  }
  for (const ModelPart& p : model->parts) {
    if (p.name == name) return p.shape;
  }
  throw std::invalid_argument("part \"" + name + "\" is not in the model " + model->name);
}

// A learn result carries its parts' shapes in its details (learn_json).
Superquadric learnt_shape(const DetectionResult& r, const std::string& name) {
  for (const auto& p : r.details.at("parts")) {
    if (p.at("name").get<std::string>() != name) continue;
    const auto &a = p.at("size"), &e = p.at("shape"), &k = p.at("taper");
    return {a.at(0).get<double>(), a.at(1).get<double>(), a.at(2).get<double>(),
            e.at(0).get<double>(), e.at(1).get<double>(), k.at(0).get<double>(),
            k.at(1).get<double>()};
  }
  throw std::invalid_argument("part \"" + name + "\" is not in the learnt model");
}

// An object part's scores in the details (object_result_json): its instance's part of that name.
std::optional<PartScores> object_scores(const DetectionResult& r, const PartPose& p) {
  if (!r.details.is_object()) return {};
  const auto instances = r.details.find("instances");
  if (instances == r.details.end() || !instances->is_array() || p.instance >= instances->size()) {
    return {};
  }
  const nlohmann::json& inst = (*instances)[p.instance];
  const auto parts = inst.is_object() ? inst.find("parts") : inst.end();
  if (parts == inst.end() || !parts->is_array()) return {};
  for (const nlohmann::json& part : *parts) {
    if (!part.is_object() || part.value("name", nlohmann::json()) != p.name) continue;
    return part_scores_from_json(part.value("scores", nlohmann::json()));
  }
  return {};
}

// A pipe's outer wall (walls = both) has its own radius in the details.
double wall_radius(const DetectionResult& r, const PartPose& p) {
  if (p.name == "outer" && r.details.is_object() && r.details.contains("outer")) {
    return r.details["outer"].value("radius_mm", r.bore_radius_mm);
  }
  return r.bore_radius_mm;
}

// A cone's or ellipse's fitted shape in the details (the bore itself, not a pipe's outer wall).
std::optional<BoreShape> bore_shape(const DetectionResult& r, const PartPose& p) {
  if (p.name == "outer" || !r.details.is_object() || !r.details.contains("shape")) return {};
  return bore_shape_from_json(r.details["shape"]);
}

}  // namespace

render::Drawing result_drawing(const DetectionResult& r, const ObjectModel* model) {
  render::Drawing d;
  d.legend.push_back(std::string(to_string(r.kind)) + " request " + r.request_id +
                     (r.model.empty() ? "" : " (" + r.model + ")") +
                     (r.found ? ": found" : ": not found: " + r.reason));
  for (const PartPose& p : r.parts) {
    const Eigen::Vector3d c = p.T_world_part.translation(), z = p.T_world_part.linear().col(2);
    if (r.kind == DetectKind::kBore) {
      // The service's result has no entrance plane: the renderer estimates it from the scan.
      const double radius = wall_radius(r, p);
      const std::optional<BoreShape> shape = bore_shape(r, p);
      d.bores.push_back({c, z, radius, Eigen::Vector3d::Zero(), 0.0, shape});
      d.legend.push_back(p.name + " entrance  " + legend_vector(c) + " mm");
      d.legend.push_back("axis      " + legend_vector(z) + " (out of the bore)");
      d.legend.push_back(legend_format("radius    %.3f mm, score %.3f", radius, p.score));
      if (shape) d.legend.push_back(render::shape_line(*shape));
    } else if (r.kind == DetectKind::kCalibrate) {
      d.legend.push_back(p.name + "  " + legend_vector(c) + " mm, z-axis " + legend_vector(z) +
                         " (calibrated, not applied)");
    } else {
      const Superquadric shape =
          r.kind == DetectKind::kLearn ? learnt_shape(r, p.name) : shape_of(model, p.name);
      d.parts.push_back({p.name, shape, p.T_world_part});
      d.legend.push_back(legend_format("[%u] ", p.instance) + p.name + "  centre " +
                         legend_vector(c) + " mm, z-axis " + legend_vector(z) +
                         legend_format(", score %.3f", p.score));
      if (const std::optional<PartScores> s = object_scores(r, p)) {
        d.legend.push_back(render::scores_line(*s));
      }
    }
  }
  d.legend.push_back(
      legend_format("scan %.2f s, detection %.3f s", r.scan_seconds, r.detect_seconds));
  return d;
}

bool write_result_picture(const std::filesystem::path& path, const PointCloud& cloud,
                          const DetectionResult& result, const ObjectModel* model,
                          std::string* error) {
  render::Drawing drawing;
  try {
    drawing = result_drawing(result, model);
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  render::RenderOptions options;
  options.colouring =
      drawing.empty() ? render::Colouring::kHeight : render::Colouring::kModelDistance;
  const bool ok = render::write_detection_png(path.string(), cloud, drawing, options, error);
  render::release_font_caches();
  return ok;
}

}  // namespace rangefit::daemon
