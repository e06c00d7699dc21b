#pragma once
// Moments of exact radius neighbourhoods, fast: the index behind estimate_normals_binned.
// Points are binned on a 2-D grid of cells on the plane normal to a direction (the view: a range
// scan is nearly a height field along it), each cell's points stored contiguously as floats. A
// query's ball then covers a few short rows of cells, each scanned with a SIMD loop (4 or 8
// lanes, picked at run time from the CPU) that tests |x - p| <= R exactly and sums x - p and
// (x - p)(x - p)^T. Offsets are single precision (~1e-6 mm at 50 mm from the grid centre), far
// below any sensor noise; sums are returned in double.

#include <Eigen/Core>
#include <cstdint>
#include <memory_resource>
#include <span>
#include <vector>

#include "detect/common/pca.hpp"

namespace rangefit {

class NeighbourGrid {
 public:
  // `cell`: the grid cell size, mm (grown for sparse clouds so cells stay ~ points / 4).
  // Non-finite points are left out. The grid's buffers come from `mr`.
  NeighbourGrid(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& dir, double cell,
                std::pmr::memory_resource* mr = std::pmr::get_default_resource());
  // Only points[subset[i]]: a region of a larger cloud, without copying it first.
  NeighbourGrid(std::span<const Eigen::Vector3d> points, std::span<const std::uint32_t> subset,
                const Eigen::Vector3d& dir, double cell,
                std::pmr::memory_resource* mr = std::pmr::get_default_resource());

  // Count, sum and sum of outer products (world frame) of the offsets x - p of every point x
  // with |x - p| <= radius. Empty moments for a non-finite p or an empty grid.
  pca::Moments ball(const Eigen::Vector3d& p, double radius) const;

  // The SIMD width in use (4 or 8 float lanes: SSE2/NEON, or AVX2 when the CPU has it).
  static int lanes();

  // The layout the scan kernels read (public so the kernels can be free functions).
  struct View {
    const float *x, *y, *z;
    const std::uint32_t* start;  // first sorted point of each cell; start[cells] is the end
    double cell, inv_cell, lo_u, lo_v;  // inv_cell: 1 / cell, as the cells were assigned
    int nu, nv;
  };

 private:
  void build(std::span<const Eigen::Vector3d> points, const std::uint32_t* subset, std::size_t n,
             const Eigen::Vector3d& dir, double cell);

  Eigen::Matrix3d basis_ = Eigen::Matrix3d::Identity();  // columns e1, e2, e3 (= dir)
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  double lo_u_ = 0.0, lo_v_ = 0.0;  // grid corner in the centred (u, v) frame
  int nu_ = 0, nv_ = 0;
  std::pmr::vector<std::uint32_t> start_;
  std::pmr::vector<float> x_, y_, z_;  // padded by 16 far-away points for the tail loads
};

}  // namespace rangefit
