#include "daemon/service/result_picture.hpp"

#include <cstdio>
#include <stdexcept>

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
      d.bores.push_back({c, z, r.bore_radius_mm, Eigen::Vector3d::Zero(), 0.0});
      d.legend.push_back("entrance  " + legend_vector(c) + " mm");
      d.legend.push_back("axis      " + legend_vector(z) + " (out of the bore)");
      d.legend.push_back(legend_format("radius    %.3f mm, score %.3f", r.bore_radius_mm, p.score));
    } else {
      d.parts.push_back({p.name, shape_of(model, p.name), p.T_world_part});
      d.legend.push_back(legend_format("[%u] ", p.instance) + p.name + "  centre " +
                         legend_vector(c) + " mm, z-axis " + legend_vector(z) +
                         legend_format(", score %.3f", p.score));
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
