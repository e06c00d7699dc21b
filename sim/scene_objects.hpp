#pragma once
// Objects of the varied scenes (sim/varied_scene.hpp): the table 5.2 models (thesis ch. 5) and
// the mallet, resting poses on the table (z up, surface z = 0), look-alikes and other clutter,
// and the overlap test that keeps objects out of each other (oriented bounding boxes).

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "detect/object/object_model.hpp"
#include "sim/superquadric_raycast.hpp"

namespace rangefit::sim {

// Table 5.2: cylinder 30,30,50 e 0.1,1; box 25,25,50 e 0.1,0.1; sphere 50; cone 20,20,40 e 0.1,1
// taper -1,-1 (base radius 40 at z = -40, tip at +40). Mallet: head 30,30,56 and shaft 12,10,120
// (both e 0.1,1), their axes at 90 deg and centres 170 mm apart.
// The pose whose z-axis is `z` (turned by spin about it) at `centre`.
Eigen::Isometry3d pose_from_axis(const Eigen::Vector3d& centre, const Eigen::Vector3d& z,
                                 double spin_rad = 0.0);
// A one-part model.
ObjectModel single(const std::string& name, const Superquadric& sq);

// The thesis scenes' parts with their poses: fig. 5.18 (table 5.3: cylinder, box, sphere,
// cone), fig. 5.28 (spheres of 48, 50 and 52 mm; the 50 is index 1) and the mallet (parts 0, 1)
// among a drum, a rod, a hammer and two occluding boxes.
std::vector<ScenePart> fig_5_18_parts();
std::vector<ScenePart> three_spheres_parts();
std::vector<ScenePart> mallet_scene_parts();

Superquadric cylinder_model();
Superquadric box_model();
Superquadric sphere_model();
Superquadric cone_model();
ObjectModel mallet_model();

// How a part may rest on the table: on its base only (tapered parts, the cone), or on any of
// the faces across its axes (z, x or y up, untapered parts; for a sphere all are alike).
enum class Rest { kBase, kAnyFace };
Rest rest_of(const Superquadric& sq);  // kBase for tapered parts

// One object: one part, or a linked few (the mallet).
struct TableObject {
  std::string name;
  std::vector<ScenePart> parts;
};

// A single part resting at table position (x, y) with yaw about z, face up drawn when kAnyFace
// (z up with probability p_standing, else x or y up).
TableObject resting_part(const std::string& name, const Superquadric& sq, Rest rest,
                         std::mt19937_64& rng, double p_standing = 0.5);
// The mallet (or a look-alike of it: sizes and link distance x scale, head x head_scale) lying
// on the table: the head on its side, the shaft's far end on the table, so the shaft tilts.
TableObject resting_mallet(const std::string& name, std::mt19937_64& rng, double scale = 1.0,
                           double head_scale = 1.0);

// A look-alike of the model: (1 +- ratio) x all its sizes, or only across or only along its
// axis; of a compound model (the mallet), the whole object or its first part (the head).
TableObject lookalike(const ObjectModel& model, double ratio, std::mt19937_64& rng);
// Random clutter: cans, boxes, balls, superquadrics, tapered parts standing; for a compound
// model (the mallet) also its lone parts and a hammer (a head half the size on the shaft), as in
// the thesis mallet scene. Never a part within min_ratio of a model part (similar_size).
TableObject clutter_object(const ObjectModel& model, double min_ratio, std::mt19937_64& rng);

// Moves the object so that its bounds' centre is at (x, y) and rotates it by yaw about the
// vertical through that centre.
void place(TableObject& o, double x, double y, double yaw);

struct OrientedBox {
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;  // columns
  Eigen::Vector3d half;
};
OrientedBox oriented_bounds(const ScenePart& p);
// Separating-axis test; true when the boxes come closer than `gap_mm` (touching counts for 0).
bool boxes_overlap(const OrientedBox& a, const OrientedBox& b, double gap_mm);
bool objects_overlap(const TableObject& a, const TableObject& b, double gap_mm);
// Axis-aligned table-frame bounds of the object's part boxes.
Eigen::AlignedBox3d object_bounds(const TableObject& o);
// max over the object's part boxes of u . x: how far it reaches along u.
double reach(const TableObject& o, const Eigen::Vector3d& u);

// True when the two parts have sizes within `ratio` of each other (sorted half sizes), whatever
// their shape exponents: random clutter that close to a model part would be a true instance.
bool similar_size(const Superquadric& a, const Superquadric& b, double ratio);

}  // namespace rangefit::sim
