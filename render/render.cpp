#include "render/render.hpp"

#include <cairo.h>
#include <fontconfig/fontconfig.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "render/colour_map.hpp"
#include "render/legend_text.hpp"
#include "render/model_geometry.hpp"
#include "render/sensor_direction.hpp"

namespace rangefit::render {
namespace {

constexpr int kLineHeight = 17;  // legend text, px
constexpr double kFontSize = 12.0;
constexpr Rgb kTextColour{222, 224, 228};

using Cairo = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

// Cairo's text path shares process-wide font caches that are not safe to use from two threads
// at once (cairo 1.16 asserts in cairo_scaled_font_destroy), and release_font_caches() tears
// them down; two services in one process, or a command and a test, may draw concurrently. Every
// use of cairo here holds this lock: a picture is drawn once per detection, so the wait is short.
std::mutex& cairo_lock() {
  static std::mutex m;
  return m;
}

void set_colour(cairo_t* cr, Rgb c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, alpha);
}

// The models as lines, their entrances, and the point set a framing view should show.
struct Models {
  std::vector<Polyline> lines;
  std::vector<std::pair<Eigen::Vector3d, double>> entrances;  // and the bore radius
  std::vector<Eigen::Vector3d> extent;                        // every wireframe point
  double smallest_size = std::numeric_limits<double>::infinity();
};

Models build_models(const PointCloud& cloud, const Drawing& drawing) {
  Models m;
  for (const DrawnBore& b : drawing.bores) {
    auto lines = bore_wireframe(b, bore_depth(b, cloud.points));
    m.lines.insert(m.lines.end(), lines.begin(), lines.end());
    m.entrances.emplace_back(b.entrance, b.radius);
    m.smallest_size = std::min(m.smallest_size, b.radius);
  }
  for (const DrawnPart& p : drawing.parts) {
    auto lines = part_wireframe(p);
    m.lines.insert(m.lines.end(), lines.begin(), lines.end());
    m.smallest_size = std::min(m.smallest_size, p.shape.min_size());
  }
  for (const Polyline& l : m.lines)
    m.extent.insert(m.extent.end(), l.points.begin(), l.points.end());
  return m;
}

Eigen::Vector3d centroid(std::span<const Eigen::Vector3d> points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    sum += p;
    ++n;
  }
  return n ? Eigen::Vector3d(sum / static_cast<double>(n)) : Eigen::Vector3d::Zero();
}

// Direction toward the sensor for the left panel and its title.
std::pair<Eigen::Vector3d, std::string> sensor_direction(const PointCloud& cloud,
                                                         const Drawing& drawing,
                                                         const Models& models,
                                                         const RenderOptions& o) {
  const auto finite = [](const Eigen::Vector3d& v) { return v.allFinite() && v.norm() > 1e-9; };
  if (o.toward_sensor && finite(*o.toward_sensor)) return {*o.toward_sensor, "sensor view"};
  if (o.sensor_position && o.sensor_position->allFinite()) {
    const Eigen::Vector3d c =
        models.extent.empty() ? centroid(cloud.points) : centroid(models.extent);
    const Eigen::Vector3d d = *o.sensor_position - c;
    if (finite(d)) return {d, "sensor view"};
  }
  // The sensor the scan says took it, looking at the models (or at the scan's middle).
  const Eigen::Vector3d target =
      models.extent.empty() ? centroid(cloud.points) : centroid(models.extent);
  if (const auto toward = toward_scan_sensor(cloud.sensor, target)) {
    return {*toward, "sensor view"};
  }
  if (!drawing.bores.empty() && finite(drawing.bores.front().axis)) {
    return {drawing.bores.front().axis, "along the bore axis"};
  }
  return {Eigen::Vector3d(0.0, -0.6, 0.8), "oblique view (sensor unknown)"};
}

void frame(Panel& panel, const PointCloud& cloud, const Models& models, const RenderOptions& o) {
  OrthoView& v = panel.view;
  if (o.px_per_mm > 0.0) {
    v.width = o.panel_width;
    v.height = o.panel_height;
    v.centre = o.look_at;
    v.px_per_mm = o.px_per_mm;
  } else if (o.zoom_to_models && !models.extent.empty()) {
    fit_to(v, models.extent, o.panel_width, o.panel_height, 0.0);
    v.px_per_mm *= 0.45;  // the model fills half the panel, its surroundings the rest
  } else {
    fit_to(v, cloud.points, o.panel_width, o.panel_height, 0.04, 0.002);
  }
}

// Splat size in px that closes the gaps between neighbouring points: the median distance from a
// sample of the panel's points to their third nearest projected neighbour (a coarse grid),
// within 1..12 px so a sparse scan still reads as a surface and detail survives. 0: no point in
// the panel.
int splat_size(const OrthoView& v, std::span<const Eigen::Vector3d> points) {
  constexpr double kCell = 8.0;  // px
  const auto key = [](long cx, long cy) { return (cx << 32) ^ (cy & 0xffffffffL); };
  std::unordered_map<long, std::vector<Eigen::Vector2d>> cells;
  std::vector<Eigen::Vector2d> inside;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    const Eigen::Vector2d q = v.project(p);
    if (q.x() < 0 || q.y() < 0 || q.x() >= v.width || q.y() >= v.height) continue;
    inside.push_back(q);
    cells[key(std::lround(std::floor(q.x() / kCell)), std::lround(std::floor(q.y() / kCell)))]
        .push_back(q);
  }
  if (inside.empty()) return 0;
  std::vector<double> nearest;
  const std::size_t step = std::max<std::size_t>(1, inside.size() / 256);
  for (std::size_t i = 0; i < inside.size(); i += step) {
    const Eigen::Vector2d& q = inside[i];
    const long cx = std::lround(std::floor(q.x() / kCell)),
               cy = std::lround(std::floor(q.y() / kCell));
    // The third nearest: on a scan grid with rows farther apart than columns the two nearest
    // are in the same row, the third in the next one.
    std::array<double, 3> best{2.0 * kCell, 2.0 * kCell, 2.0 * kCell};
    for (long dy = -2; dy <= 2; ++dy) {
      for (long dx = -2; dx <= 2; ++dx) {
        const auto it = cells.find(key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (const Eigen::Vector2d& o : it->second) {
          const double d = (o - q).norm();
          if (d > 0.0 && d < best[2]) {
            best[2] = d;
            std::sort(best.begin(), best.end());
          }
        }
      }
    }
    nearest.push_back(best[2]);
  }
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return std::clamp(static_cast<int>(std::ceil(1.3 * nearest[nearest.size() / 2])), 1, 12);
}

// Point splats with a depth buffer (nearest point wins); returns the buffer for the lines'
// hidden-part test.
std::vector<float> draw_points(Image& image, const Panel& panel, const PointCloud& cloud,
                               const std::vector<Rgb>& colours) {
  const OrthoView& v = panel.view;
  std::vector<float> zbuf(static_cast<std::size_t>(v.width) * v.height,
                          -std::numeric_limits<float>::infinity());
  const int size = splat_size(v, cloud.points);
  if (size == 0) return zbuf;
  const int lo = -(size - 1) / 2, hi = size / 2;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite()) continue;
    const Eigen::Vector2d q = v.project(p);
    const int cx = static_cast<int>(std::floor(q.x())), cy = static_cast<int>(std::floor(q.y()));
    if (cx + hi < 0 || cy + hi < 0 || cx + lo >= v.width || cy + lo >= v.height) continue;
    const auto depth = static_cast<float>(v.depth(p));
    for (int y = std::max(0, cy + lo); y <= std::min(v.height - 1, cy + hi); ++y) {
      for (int x = std::max(0, cx + lo); x <= std::min(v.width - 1, cx + hi); ++x) {
        float& z = zbuf[static_cast<std::size_t>(y) * v.width + x];
        if (depth <= z) continue;
        z = depth;
        image.set(panel.x0 + x, panel.y0 + y, colours[i]);
      }
    }
  }
  return zbuf;
}

Rgb role_colour(LineRole role) {
  switch (role) {
    case LineRole::kModel:
      return kModelColour;
    case LineRole::kAxis:
      return kBoreAxisColour;
    case LineRole::kAxisX:
      return {255, 72, 72};
    case LineRole::kAxisY:
      return {72, 230, 72};
    case LineRole::kAxisZ:
      return {80, 150, 255};
  }
  return kModelColour;
}

// A closed model's own far side: its normal points away from the viewer (the silhouette, where
// it is perpendicular, stays bright; a degenerate normal counts as facing the viewer).
bool faces_away(const OrthoView& v, const Eigen::Vector3d& normal) {
  return normal.dot(v.toward) < -0.02 * normal.norm();
}

// Behind the scan: nearer points cover most of the pixels around, so gaps in the scan do not
// make a line under the surface bright.
bool buried(const OrthoView& v, const std::vector<float>& zbuf, const Eigen::Vector3d& p,
            double tolerance) {
  const Eigen::Vector2d m = v.project(p);
  if (!m.allFinite()) return false;
  const int mx = static_cast<int>(std::floor(m.x())), my = static_cast<int>(std::floor(m.y()));
  const auto limit = static_cast<float>(v.depth(p) + tolerance);
  int covered = 0, total = 0;
  for (int y = my - 3; y <= my + 3; ++y) {
    for (int x = mx - 3; x <= mx + 3; ++x) {
      ++total;
      if (x >= 0 && y >= 0 && x < v.width && y < v.height &&
          zbuf[static_cast<std::size_t>(y) * v.width + x] > limit) {
        ++covered;
      }
    }
  }
  return 4 * covered > 3 * total;
}

// Segments behind the scanned surface (the far side of a part, the bore below the plate) are
// drawn faint, so the picture reads like the object and not like a tangle.
void draw_lines(cairo_t* cr, const Panel& panel, const std::vector<Polyline>& lines,
                const std::vector<float>& zbuf) {
  const OrthoView& v = panel.view;
  const double tolerance = std::max(1.0, 3.0 / v.px_per_mm);  // mm
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const Polyline& line : lines) {
    const bool axis = line.role != LineRole::kModel;
    cairo_set_line_width(cr, axis ? 2.2 : 1.5);
    for (std::size_t k = 1; k < line.points.size(); ++k) {
      const Eigen::Vector3d mid = 0.5 * (line.points[k - 1] + line.points[k]);
      const bool hidden = line.normals.size() == line.points.size()
                              ? faces_away(v, line.normals[k - 1] + line.normals[k])
                              : buried(v, zbuf, mid, tolerance);
      set_colour(cr, role_colour(line.role), hidden ? 0.35 : 1.0);
      const Eigen::Vector2d a = panel.pixel(line.points[k - 1]), b = panel.pixel(line.points[k]);
      cairo_move_to(cr, a.x(), a.y());
      cairo_line_to(cr, b.x(), b.y());
      cairo_stroke(cr);
    }
  }
}

// Text on a dark box, readable over any points.
void label(cairo_t* cr, double x, double y, const std::string& text, Rgb colour = kTextColour) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  set_colour(cr, kBackground, 0.7);
  cairo_rectangle(cr, x + e.x_bearing - 3.0, y + e.y_bearing - 2.0, e.width + 6.0, e.height + 4.0);
  cairo_fill(cr);
  set_colour(cr, colour);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, text.c_str());
}

// A ring and cross at the entrance, labelled beside the bore's rim (radius mm).
void draw_entrance(cairo_t* cr, const Panel& panel, const Eigen::Vector3d& entrance,
                   double radius) {
  const Eigen::Vector2d c = panel.pixel(entrance);
  set_colour(cr, kEntranceColour);
  cairo_set_line_width(cr, 2.0);
  cairo_new_sub_path(cr);
  cairo_arc(cr, c.x(), c.y(), 6.0, 0.0, 2.0 * 3.14159265358979);
  cairo_move_to(cr, c.x() - 11.0, c.y());
  cairo_line_to(cr, c.x() + 11.0, c.y());
  cairo_move_to(cr, c.x(), c.y() - 11.0);
  cairo_line_to(cr, c.x(), c.y() + 11.0);
  cairo_stroke(cr);
  label(cr, c.x() + std::max(12.0, radius * panel.view.px_per_mm + 8.0), c.y() + 4.0, "entrance",
        kEntranceColour);
}

// 1, 2 or 5 times a power of ten, near a fifth of the panel.
double scale_bar_mm(const OrthoView& v) {
  const double target = 0.2 * v.width / v.px_per_mm;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (const double f : {5.0, 2.0, 1.0}) {
    if (f * p <= target) return f * p;
  }
  return p;
}

void draw_panel_frame(cairo_t* cr, const Panel& panel) {
  const OrthoView& v = panel.view;
  label(cr, panel.x0 + 8.0, panel.y0 + 18.0, panel.title);
  const double mm = scale_bar_mm(v);
  const double x = panel.x0 + 12.0, y = panel.y0 + v.height - 14.0;
  set_colour(cr, kBackground, 0.7);
  cairo_rectangle(cr, x - 3.0, y - 3.0, mm * v.px_per_mm + 6.0, 6.0);
  cairo_fill(cr);
  set_colour(cr, kTextColour);
  cairo_set_line_width(cr, 2.0);
  cairo_move_to(cr, x, y);
  cairo_line_to(cr, x + mm * v.px_per_mm, y);
  cairo_stroke(cr);
  label(cr, x, y - 6.0, legend_format("%g mm", mm));
  // Separator between the panels.
  set_colour(cr, {70, 72, 80});
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, panel.x0 + 0.5, panel.y0 + 0.5, v.width - 1.0, v.height - 1.0);
  cairo_stroke(cr);
}

struct ColourKey {
  std::string label;
  double lo = 0.0, hi = 1.0;
  Rgb (*scale)(double) = height_colour;
};

void draw_legend(cairo_t* cr, int y0, int width, const std::vector<std::string>& lines,
                 const ColourKey& key) {
  set_colour(cr, kTextColour);
  double y = y0 + 18.0;
  for (const std::string& line : lines) {
    cairo_move_to(cr, 10.0, y);
    cairo_show_text(cr, line.c_str());
    y += kLineHeight;
  }
  // Colour key: a bar with its two ends labelled, at the right.
  const double bar_w = 180.0, bar_h = 10.0, bx = width - bar_w - 180.0, by = y0 + 10.0;
  for (int i = 0; i < static_cast<int>(bar_w); ++i) {
    set_colour(cr, key.scale(i / (bar_w - 1.0)));
    cairo_rectangle(cr, bx + i, by, 1.0, bar_h);
    cairo_fill(cr);
  }
  set_colour(cr, kTextColour);
  cairo_move_to(cr, bx, by + bar_h + 14.0);
  cairo_show_text(cr, legend_format("%.1f", key.lo).c_str());
  cairo_move_to(cr, bx + bar_w - 30.0, by + bar_h + 14.0);
  cairo_show_text(cr, legend_format("%.1f mm", key.hi).c_str());
  cairo_move_to(cr, bx, by + bar_h + 14.0 + kLineHeight);
  cairo_show_text(cr, key.label.c_str());
}

// Point colours and the key that explains them.
ColourKey colour_points(const PointCloud& cloud, const Drawing& drawing, const Models& models,
                        const Panel& top, const RenderOptions& o, std::vector<Rgb>& colours) {
  colours.assign(cloud.points.size(), kFarColour);
  ColourKey key;
  if (o.colouring == Colouring::kModelDistance && !drawing.empty()) {
    const double scale =
        o.distance_scale_mm > 0.0 ? o.distance_scale_mm : std::max(0.5, 0.1 * models.smallest_size);
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      const double d = model_distance(drawing, cloud.points[i]);
      if (d <= 4.0 * scale) colours[i] = distance_colour(d / scale);
    }
    return {"distance to the model (grey: over 4x)", 0.0, scale, distance_colour};
  }
  // Height range over the points the top panel shows, so a zoomed picture keeps its contrast.
  std::vector<double> z;
  for (const Eigen::Vector3d& p : cloud.points) {
    const Eigen::Vector2d q = top.view.project(p);
    if (p.allFinite() && q.x() >= 0 && q.y() >= 0 && q.x() < top.view.width &&
        q.y() < top.view.height) {
      z.push_back(p.z());
    }
  }
  double lo = 0.0, hi = 1.0;
  if (!z.empty()) {
    std::sort(z.begin(), z.end());
    lo = z[static_cast<std::size_t>(0.02 * static_cast<double>(z.size() - 1))];
    hi = z[static_cast<std::size_t>(0.98 * static_cast<double>(z.size() - 1))];
    if (hi - lo < 1e-6) hi = lo + 1.0;
  }
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    colours[i] = height_colour((cloud.points[i].z() - lo) / (hi - lo));
  }
  return {"height z", lo, hi, height_colour};
}

}  // namespace

Rendering render_scan(const PointCloud& cloud, const Drawing& input, const RenderOptions& options) {
  RenderOptions o = options;
  o.panel_width = std::clamp(o.panel_width, 64, 4096);
  o.panel_height = std::clamp(o.panel_height, 64, 4096);
  Drawing drawing = input;
  for (DrawnBore& b : drawing.bores) {
    if (b.plane_normal.norm() == 0.0) b.plane_normal = entrance_plane_normal(b, cloud.points);
  }
  const Models models = build_models(cloud, drawing);

  Rendering out;
  const auto [toward, title] = sensor_direction(cloud, drawing, models, o);
  out.sensor.view = look_from(toward, Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d d = out.sensor.view.toward;
  out.sensor.title = title + legend_format(" (from %.2f, %.2f, %.2f)", d.x(), d.y(), d.z());
  out.top.view = look_from(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY());
  out.top.title = "from above (+z, y up)";
  frame(out.sensor, cloud, models, o);
  frame(out.top, cloud, models, o);
  out.top.x0 = o.panel_width;

  std::vector<std::string> legend = drawing.legend;
  legend.push_back(legend_format("%zu points", cloud.points.size()));
  const int legend_height =
      16 + kLineHeight * static_cast<int>(std::max<std::size_t>(legend.size(), 3));
  out.image = Image(2 * o.panel_width, o.panel_height + legend_height, kBackground);

  std::vector<Rgb> colours;
  const ColourKey key = colour_points(cloud, drawing, models, out.top, o, colours);
  const std::vector<float> zbuf_sensor = draw_points(out.image, out.sensor, cloud, colours);
  const std::vector<float> zbuf_top = draw_points(out.image, out.top, cloud, colours);

  const std::lock_guard lock(cairo_lock());
  cairo_surface_t* surface = cairo_image_surface_create_for_data(
      reinterpret_cast<unsigned char*>(out.image.pixels.data()), CAIRO_FORMAT_RGB24,
      out.image.width, out.image.height, out.image.width * 4);
  {
    Cairo cr(cairo_create(surface), cairo_destroy);
    cairo_select_font_face(cr.get(), "DejaVu Sans Mono", CAIRO_FONT_SLANT_NORMAL,
                           CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr.get(), kFontSize);
    for (const auto& [panel, zbuf] :
         {std::pair{&out.sensor, &zbuf_sensor}, std::pair{&out.top, &zbuf_top}}) {
      cairo_save(cr.get());
      cairo_rectangle(cr.get(), panel->x0, panel->y0, panel->view.width, panel->view.height);
      cairo_clip(cr.get());
      draw_lines(cr.get(), *panel, models.lines, *zbuf);
      for (const auto& [e, radius] : models.entrances) draw_entrance(cr.get(), *panel, e, radius);
      draw_panel_frame(cr.get(), *panel);
      cairo_restore(cr.get());
    }
    draw_legend(cr.get(), o.panel_height, out.image.width, legend, key);
  }
  cairo_surface_flush(surface);
  cairo_surface_destroy(surface);
  return out;
}

bool write_detection_png(const std::string& path, const PointCloud& cloud, const Drawing& drawing,
                         const RenderOptions& options, std::string* error) {
  return write_png(render_scan(cloud, drawing, options).image, path, error);
}

void release_font_caches() {
  const std::lock_guard lock(cairo_lock());
  cairo_debug_reset_static_data();
  FcFini();
}

}  // namespace rangefit::render
