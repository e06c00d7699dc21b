#pragma once
// Exact ray/superquadric intersection and a simple single-view scene renderer built on it, for
// tests, benchmarks and the sensor simulator (sim/superquadric_adapter.cpp calls the free
// function from its Embree user geometry).

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "detect/common/point_cloud.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit::sim {

// First t in (t_min, t_max] where origin + t dir enters the tapered superquadric posed by
// T_world_part (dir need not be unit; t is in units of |dir|). The hit lies on the surface to
// 1e-6 mm. nullopt when the ray misses, the part is invalid or the input is not finite.
std::optional<double> intersect_superquadric(const Superquadric& sq,
                                             const Eigen::Isometry3d& T_world_part,
                                             const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& dir, double t_max,
                                             double t_min = 0.0);

// Outward unit normal of the posed part at a world point on (or near) its surface.
Eigen::Vector3d superquadric_normal(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                                    const Eigen::Vector3d& p_world);

struct ScenePart {
  std::string name;  // e.g. "cylinder", "mallet/head", "occluder"
  Superquadric model;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
};

// A pinhole view of a table scene: the table is the rectangle [min, max] at z = table_z.
struct SceneView {
  Eigen::Vector3d eye = Eigen::Vector3d(150.0, -250.0, 450.0);  // mm
  Eigen::Vector3d target = Eigen::Vector3d(150.0, 100.0, 20.0);
  double fov_deg = 60.0;  // horizontal field of view
  int width = 440;
  int height = 330;
  bool table = true;
  double table_z = 0.0;
  Eigen::Vector2d table_min = Eigen::Vector2d(-60.0, -40.0);
  Eigen::Vector2d table_max = Eigen::Vector2d(360.0, 280.0);
  double noise_sigma_mm = 0.0;  // Gaussian noise added to x, y and z of each point
  std::uint64_t noise_seed = 1;
};

struct RenderedScene {
  PointCloud cloud;                 // world frame, mm
  std::vector<std::int32_t> label;  // per point: part index, or -1 for the table
};

// Casts one ray per pixel and keeps the nearest hit of the table and all parts.
RenderedScene render_scene(const std::vector<ScenePart>& parts, const SceneView& view);

}  // namespace rangefit::sim
