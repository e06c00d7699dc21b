#pragma once
// An evenly spread subset of a dense region: the first point in each cube of a voxel grid whose
// size is chosen so that about `target` cubes are occupied. Spread by surface area, not by point
// count, so a wall seen at a grazing angle keeps as many samples per mm^2 as the plane seen
// head-on, and a double-covered scan no more than a single one. Deterministic (scan order).

#include <Eigen/Core>
#include <cstdint>
#include <memory_resource>
#include <span>
#include <vector>

namespace rangefit {

struct SpreadSubset {
  std::pmr::vector<std::uint32_t> indices;  // kept entries of the input indices (all when few)
  double cell = 0.0;                   // voxel size, mm; 0: every index kept
  double area = 0.0;                   // surface area the points cover (occupied cells), mm^2
};

// indices: into points, all within `half` of `centre` in every coordinate (others are dropped).
// Fewer than or as many as `target` indices: all are kept. Every buffer comes from `mr`.
SpreadSubset spread_subset(std::span<const Eigen::Vector3d> points,
                           std::span<const std::uint32_t> indices, const Eigen::Vector3d& centre,
                           double half, std::size_t target,
                           std::pmr::memory_resource* mr = std::pmr::get_default_resource());

}  // namespace rangefit
