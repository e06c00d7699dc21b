#pragma once
// What a picture shows besides the scan: the fitted models and the legend's lines. Plain values,
// filled from detect/'s results (bore_drawing, object_drawing) or by a caller that only has poses
// (the service's spooled results, a result JSON read back).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "detect/bore/bore_result.hpp"
#include "detect/object/object_detector.hpp"
#include "detect/object/object_model.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit::render {

// A fitted bore: its wall from the entrance into the part (a cylinder, or the cone or ellipse
// of its shape), and the entrance plane around it.
struct DrawnBore {
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero();  // mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     // unit, out of the bore toward the sensor
  double radius = 0.0;  // mm; a cone's at the entrance, an ellipse's along shape->major_axis
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();  // zero: estimated from the scan
  double depth = 0.0;  // drawn length into the part, mm; 0: as deep as the scan shows the wall
  std::optional<BoreShape> shape;  // a cone or ellipse as fitted; empty: a circular cylinder
};

// A fitted superquadric part at its pose.
struct DrawnPart {
  std::string name;
  Superquadric shape;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
};

struct Drawing {
  std::vector<DrawnBore> bores;
  std::vector<DrawnPart> parts;
  std::vector<std::string> legend;  // text lines under the pictures, drawn as given
  bool empty() const { return bores.empty() && parts.empty(); }
};

// The found bore (none when not found) and the numbers: entrance, axis, radius, a cone's or
// ellipse's shape, point counts, time; or why it was not found.
Drawing bore_drawing(const BoreResult& result);

// The legend's line of a cone's half-angle and cylinder, or an ellipse's radius2 and major axis.
std::string shape_line(const BoreShape& shape);

// Every part of every instance found, each with its pose and scores, and the time.
Drawing object_drawing(const ObjectModel& model, const ObjectDetectResult& result);

// One part's fit scores as every legend prints them: M, I, S (eq. 5.2-5.4), the share of what the
// sensor could have measured that the scan covers, and the share it saw through.
std::string scores_line(const PartScores& s);

}  // namespace rangefit::render
