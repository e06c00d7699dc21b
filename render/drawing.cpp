#include "render/drawing.hpp"
#include "render/legend_text.hpp"

#include <cstdio>
#include <numbers>
#include <string>

namespace rangefit::render {
namespace {

std::string vec(const Eigen::Vector3d& v, const char* digits = "%.3f") {
  const std::string f = std::string(digits) + ", " + digits + ", " + digits;
  return legend_format(f.c_str(), v.x(), v.y(), v.z());
}

constexpr double kDeg = 180.0 / std::numbers::pi;

}  // namespace

std::string shape_line(const BoreShape& s) {
  if (!s.cone) {
    return legend_format("ellipse   radius2 %.3f mm, major axis ", s.radius2) +
           vec(s.major_axis, "%.4f");
  }
  return legend_format("cone      half-angle %.3f deg", s.half_angle * kDeg) +
         (s.cylinder_radius > 0.0 ? legend_format(", into a cylinder of %.3f mm", s.cylinder_radius)
                                  : std::string());
}

Drawing bore_drawing(const BoreResult& r) {
  Drawing d;
  if (!r.found) {
    d.legend.push_back("bore not found: " + std::string(to_string(r.reason)));
  } else {
    d.bores.push_back({r.entrance, r.axis, r.radius, r.plane_normal, 0.0, r.shape});
    d.legend.push_back("bore found" + std::string(r.refined ? ", refined" : "") +
                       (r.second_fit ? ", notch re-fit" : ""));
    d.legend.push_back("entrance  " + vec(r.entrance) + " mm");
    d.legend.push_back("axis      " + vec(r.axis, "%.4f") + " (out of the bore)");
    d.legend.push_back(
        legend_format("radius    %.3f mm (before refinement %.3f mm)", r.radius, r.rsf_radius));
    if (r.shape) d.legend.push_back(shape_line(*r.shape));
  }
  const BoreCounts& c = r.counts;
  d.legend.push_back(legend_format("points    %zu in region, %zu plane, %zu wall (%zu in last fit)",
                                   c.roi, c.plane, c.wall, c.wall_final));
  d.legend.push_back(legend_format("time      %.1f ms", r.time_ms.total));
  return d;
}

std::string scores_line(const PartScores& s) {
  return legend_format("      M %.4f  I %zu  S %zu  coverage %.2f  seen through %.2f", s.measure,
                       s.interior, s.surface, s.coverage, s.seen_through);
}

Drawing object_drawing(const ObjectModel& model, const ObjectDetectResult& r) {
  Drawing d;
  d.legend.push_back(
      model.name +
      (r.found() ? ": found" : ": not found (" + std::string(to_string(r.reason)) + ")") +
      legend_format(", %d hypotheses, %.1f ms", r.hypotheses_evaluated, r.time.total_ms));
  for (std::size_t i = 0; i < r.instances.size(); ++i) {
    for (const DetectedPart& p : r.instances[i].parts) {
      Superquadric shape;
      for (const ModelPart& mp : model.parts) {
        if (mp.name == p.name) shape = mp.shape;
      }
      d.parts.push_back({p.name, shape, p.T_world_part});
      d.legend.push_back(legend_format("[%zu] ", i) + p.name + "  centre " +
                         vec(p.center(), "%.2f") + " mm, z-axis " + vec(p.z_axis()));
      d.legend.push_back(scores_line(p.scores));
    }
  }
  return d;
}

}  // namespace rangefit::render
