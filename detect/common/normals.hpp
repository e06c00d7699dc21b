#pragma once
// Surface normals by PCA over all points within R of each query point (thesis 4.1.1), oriented
// toward the sensor and kept only if the neighbourhood's centroid lies within 0.1 R of the point
// (eq. 4.4), which rejects the skewed patches at boundaries and rims. Neighbours always come from
// the full-resolution points, so sub-sampling only thins out the query points.

#include <Eigen/Core>
#include <cstdint>
#include <memory_resource>
#include <optional>
#include <span>
#include <vector>

#include "detect/common/kdtree.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit {

struct NormalOptions {
  double radius = 2.0;               // R: neighbourhood radius, mm (thesis: 2 mm)
  double max_centroid_offset = 0.1;  // keep if mu < this * R (eq. 4.4)
  int min_neighbours = 6;            // fewer neighbours (self included): no normal
  // Orientation: toward sensor_position when set, else along view_dir (unit, toward the sensor).
  Eigen::Vector3d view_dir = Eigen::Vector3d::UnitZ();
  std::optional<Eigen::Vector3d> sensor_position;
};

// One entry per query: a unit normal, or zero when the point was rejected (too few neighbours,
// degenerate patch, or the eq. 4.4 centroid test failed).
struct NormalEstimate {
  std::pmr::vector<Eigen::Vector3d> normals;
  std::size_t kept = 0;
};

// Unorganised: neighbours of points[queries[i]] are searched in `tree`, built over `points`.
NormalEstimate estimate_normals(std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                std::span<const std::uint32_t> queries,
                                const NormalOptions& options);

// Exact and fast, organised or not: the same neighbourhoods as the k-d tree (every point within
// R), found through a 2-D grid of cells on the plane normal to the view direction. A range scan
// is nearly a height field along its view, so a query's ball covers a few short rows of cells,
// each stored contiguously and scanned with SIMD-friendly loops (single-precision offsets of
// ~1e-6 mm, far below any sensor noise). Non-finite points are ignored; a non-finite query gets
// no normal. Every buffer, the result's included, comes from `mr`.
NormalEstimate estimate_normals_binned(std::span<const Eigen::Vector3d> points,
                                       std::span<const std::uint32_t> queries,
                                       const NormalOptions& options,
                                       std::pmr::memory_resource* mr = std::pmr::get_default_resource());

// The same with neighbours only among points[neighbours[i]] (a region of a larger cloud) and
// queries indexing `points` too.
NormalEstimate estimate_normals_binned(std::span<const Eigen::Vector3d> points,
                                       std::span<const std::uint32_t> neighbours,
                                       std::span<const std::uint32_t> queries,
                                       const NormalOptions& options,
                                       std::pmr::memory_resource* mr = std::pmr::get_default_resource());

// Organised: neighbours come from a window of the scan grid around each query, sized from the
// grid's median cell spacing, then filtered by 3-D distance. Falls back to nothing (all zero)
// when the cloud has no grid.
NormalEstimate estimate_normals_organised(const PointCloud& cloud,
                                          std::span<const std::uint32_t> queries,
                                          const NormalOptions& options);

// Every k-th of `indices` so that about `keep` (0..1] of them remain (thesis keeps 20 %).
std::pmr::vector<std::uint32_t> subsample_evenly(std::span<const std::uint32_t> indices, double keep,
                                                 std::pmr::memory_resource* mr = std::pmr::get_default_resource());

}  // namespace rangefit
