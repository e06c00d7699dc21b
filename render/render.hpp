#pragma once
// A picture of a scan and what was found in it: two panels side by side, the scan seen from the
// sensor and from above (orthographic, points coloured by height or by distance to the fitted
// model), the models drawn over it as wireframes with their axes and the bore entrance marked,
// and a legend with the numbers underneath. For commissioning a cell and for looking at a failed
// run: the service writes one per detection, `rangefit render|bore|object --png` on demand.

#include <Eigen/Core>
#include <optional>
#include <string>

#include "detect/common/point_cloud.hpp"
#include "render/drawing.hpp"
#include "render/image.hpp"
#include "render/view.hpp"

namespace rangefit::render {

enum class Colouring {
  kHeight,         // world z, from the 2nd to the 98th percentile of the scan
  kModelDistance,  // distance to the nearest model, green 0 to red at distance_scale_mm
};

struct RenderOptions {
  int panel_width = 560;  // px, each of the two panels
  int panel_height = 480;
  Colouring colouring = Colouring::kHeight;
  // kModelDistance: red from here on, and grey beyond 4x (points of other things); 0: a tenth of
  // the smallest model size, at least 0.5 mm.
  double distance_scale_mm = 0.0;
  // Where the sensor was, for the first panel: the direction from the scene toward it (e.g. the
  // bore options' view_dir), or its position. Neither: from the sensor the cloud says took it
  // (cloud.sensor, render/sensor_direction.hpp), else along the first bore's axis, else
  // obliquely from above (-y, +z).
  std::optional<Eigen::Vector3d> toward_sensor;
  std::optional<Eigen::Vector3d> sensor_position;
  // Frame the models with their own size around them (the whole scan when there are none, or
  // when false).
  bool zoom_to_models = true;
  // A fixed camera instead of framing: both panels centred on look_at at px_per_mm (tests,
  // series of pictures at one scale). Used when px_per_mm > 0.
  Eigen::Vector3d look_at = Eigen::Vector3d::Zero();
  double px_per_mm = 0.0;
};

// One panel: its view and where it sits in the picture.
struct Panel {
  std::string title;
  OrthoView view;
  int x0 = 0;
  int y0 = 0;
  // Picture pixel of a world point.
  Eigen::Vector2d pixel(const Eigen::Vector3d& p) const {
    return view.project(p) + Eigen::Vector2d(x0, y0);
  }
};

struct Rendering {
  Image image;
  Panel sensor;  // left
  Panel top;     // right
};

// Colours of the picture, for readers of it (tests, a web page's key).
inline constexpr Rgb kBackground{24, 26, 31};
inline constexpr Rgb kModelColour{255, 255, 255};
inline constexpr Rgb kBoreAxisColour{255, 214, 0};
inline constexpr Rgb kEntranceColour{255, 64, 200};

Rendering render_scan(const PointCloud& cloud, const Drawing& drawing,
                      const RenderOptions& options = {});

// render_scan, then write_png. The service calls this once per detection for its spool entry;
// false and *error when the file cannot be written (the detection itself is unaffected).
bool write_detection_png(const std::string& path, const PointCloud& cloud, const Drawing& drawing,
                         const RenderOptions& options, std::string* error);

// Frees cairo's and fontconfig's process-wide font caches (the legend's font), which otherwise
// live until exit and show up as leaks under LeakSanitizer. It waits for a picture being drawn
// in another thread; the next picture builds the caches again.
void release_font_caches();

}  // namespace rangefit::render
