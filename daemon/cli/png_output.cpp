#include "daemon/cli/png_output.hpp"

#include <iostream>

#include "render/render.hpp"

namespace rangefit::cli {
namespace {

bool write(const std::string& path, const PointCloud& cloud, const render::Drawing& drawing,
           const render::RenderOptions& options) {
  std::string error;
  const bool ok = render::write_detection_png(path, cloud, drawing, options, &error);
  render::release_font_caches();  // the command draws one picture
  if (ok) return true;
  std::cerr << "rangefit: --png: " << error << "\n";
  return false;
}

}  // namespace

bool write_png_if_asked(const std::string& path, const PointCloud& cloud, const BoreResult& result,
                        const BoreOptions& options) {
  if (path.empty()) return true;
  render::RenderOptions o;
  o.toward_sensor = options.view_dir;
  o.sensor_position = options.sensor_position;
  o.colouring = result.found ? render::Colouring::kModelDistance : render::Colouring::kHeight;
  return write(path, cloud, render::bore_drawing(result), o);
}

bool write_png_if_asked(const std::string& path, const PointCloud& cloud, const ObjectModel& model,
                        const ObjectDetectResult& result, const ObjectDetectOptions& options) {
  if (path.empty()) return true;
  render::RenderOptions o;
  o.sensor_position = options.viewpoint;
  o.colouring = result.found() ? render::Colouring::kModelDistance : render::Colouring::kHeight;
  return write(path, cloud, render::object_drawing(model, result), o);
}

}  // namespace rangefit::cli
