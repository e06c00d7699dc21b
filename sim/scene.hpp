#pragma once
// A simulated scene: objects (analytic primitives or triangle meshes) at poses, in mm, plus the
// mounting of the sensors that scan it and ground truth for the detectors. Loaded from TOML by
// load_scene() (sim/scene_loader.hpp); ray cast by RayCaster (sim/ray_caster.hpp).
//
// Every primitive is described in its own object frame:
//   Plane     - the rectangle |x| <= size_x/2, |y| <= size_y/2 at z = 0, facing +z (one-sided
//               only in that rays from below see it too; it has no thickness).
//   Box       - the box |x| <= size_x/2, |y| <= size_y/2, |z| <= size_z/2.
//   Cylinder  - radius r around the z-axis, |z| <= height/2, closed by both caps.
//   Sphere    - radius r around the origin.
//   Superquadric - the tapered superquadric of detect/superquadric.hpp (thesis eq. 2.14-2.20).
//   Mesh      - triangles in the object frame (from STL or a generator).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "detect/object/superquadric.hpp"
#include "io/triangle_mesh.hpp"

namespace rangefit::sim {

struct PlaneShape {
  double size_x_mm = 1000.0;
  double size_y_mm = 1000.0;
};
struct BoxShape {
  Eigen::Vector3d size_mm{1.0, 1.0, 1.0};
};
struct CylinderShape {
  double radius_mm = 1.0;
  double height_mm = 1.0;
};
struct SphereShape {
  double radius_mm = 1.0;
};
// Tapered superquadric (thesis eq. 2.15 with the tapering of eq. 2.19-2.23), centred on the
// object frame's origin with its main axis along z.
struct SuperquadricShape {
  Superquadric model;
};
struct MeshShape {
  io::TriangleMesh mesh;
  std::string source;  // STL path or generator name, for messages and ground truth
};

using Shape =
    std::variant<PlaneShape, BoxShape, CylinderShape, SphereShape, SuperquadricShape, MeshShape>;

struct SceneObject {
  std::string name;
  Shape shape;
  Eigen::Isometry3d T_world_object = Eigen::Isometry3d::Identity();
};

// A bore hole the scene contains (ground truth for the bore detector, thesis ch. 4): the axis
// point on the surface where the bore opens, the axis pointing into the material, diameter.
struct BoreTruth {
  std::string name;
  Eigen::Vector3d opening_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = -Eigen::Vector3d::UnitZ();
  double diameter_mm = 0.0;
  std::string kind;  // straight, slanted, chamfered, rounded, notched
};

// Where the sensors sit in the scene. Each is the pose of that sensor's own "world" frame (the
// frame its fusion model produces points in) in scene coordinates, so the same scene can be
// scanned by each sensor without moving objects.
struct SensorMounts {
  Eigen::Isometry3d T_scene_css = Eigen::Isometry3d::Identity();      // CSS eq. 4.17 world
  Eigen::Isometry3d T_scene_stripe = Eigen::Isometry3d::Identity();   // stripe cell world
  Eigen::Isometry3d T_scene_pantilt = Eigen::Isometry3d::Identity();  // pan-tilt eq. 5.7 world
};

struct Scene {
  std::string source;  // file the scene came from, for messages
  std::vector<SceneObject> objects;
  std::vector<BoreTruth> bores;
  SensorMounts mounts;
};

}  // namespace rangefit::sim
