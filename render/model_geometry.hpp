#pragma once
// The fitted models as 3D line drawings (wireframes and axes) and the distance of a scan point
// to them, for the renderer.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "detect/bore/bore_surface.hpp"
#include "render/drawing.hpp"

namespace rangefit::render {

enum class LineRole {
  kModel,  // the model's surface: cylinder rings and generators, superquadric meridians/parallels
  kAxis,   // the bore axis
  kAxisX,  // a part frame's axes
  kAxisY,
  kAxisZ,
};

struct Polyline {
  LineRole role = LineRole::kModel;
  std::vector<Eigen::Vector3d> points;  // world, mm
  // Outward surface normals at the points of a closed model (superquadric parts): the renderer
  // dims what faces away from the viewer. Empty: the scan's depth decides what is hidden.
  std::vector<Eigen::Vector3d> normals;
};

// The drawn bore's wall as detect/ fits it: a circular cylinder, or its cone or ellipse.
BoreSurface bore_surface(const DrawnBore& bore);

// How far into the part the wall is drawn for `depth`: a pure cone no deeper than its apex.
double wall_depth(const DrawnBore& bore, double depth);

// The fitted wall (bore_surface): rings at the entrance and at wall_depth(depth) into the part,
// one between and one where a countersink's cone meets its cylinder, 12 generators through
// them, the axis from the bottom to 1.5 radii outside the entrance.
std::vector<Polyline> bore_wireframe(const DrawnBore& bore, double depth);

// Parallels and meridians of the tapered superquadric (eq. 2.14, 2.19-2.21) with their normals,
// and its x, y, z axes, each 1.3 half sizes long.
std::vector<Polyline> part_wireframe(const DrawnPart& part);

// How deep the scan shows the bore's wall: the 98th percentile of how far points within 10% of
// the radius of the wall lie behind the entrance; bore.depth when set; 2 radii when the scan
// shows no wall.
double bore_depth(const DrawnBore& bore, std::span<const Eigen::Vector3d> points);

// The entrance plane's normal when the drawing does not give one (a zero plane_normal, as in the
// service's results): the least-variance direction of the scan within two radii of the
// entrance, outside the hole, signed like the axis; the axis when fewer than 10 points are there.
Eigen::Vector3d entrance_plane_normal(const DrawnBore& bore,
                                      std::span<const Eigen::Vector3d> points);

// Distance of p to the nearest model, mm: for a bore, to its fitted wall or its entrance plane,
// whichever is nearer; for a part, along the ray from its centre (the radial Euclidean distance
// of the superquadric literature). Infinity without models.
double model_distance(const Drawing& drawing, const Eigen::Vector3d& p);

}  // namespace rangefit::render
