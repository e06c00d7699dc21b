#pragma once
// 4.1.1 region of interest at a cost bounded by what the later stages need, not by the scan.
// Every stage after it needs at most a few thousand evenly spread points (the RSF ~1000 wall
// normals, the plane and the refinement a few thousand full-resolution points each), so a dense
// region is read at a stride: a sparse probe (every 16th point of the scan) counts the region's
// points, and the scan is then read at the stride that leaves about `budget` of them. A small
// bore (region within the budget) is read at stride 1 and keeps every point. Scan order is the
// order of the rays, so every stride-th point is an evenly spread sample of an organised and an
// unorganised scan alike; the points read are copied into one compact array (cache-resident for
// the later passes) together with the normals' neighbour margin around the region.

#include <Eigen/Core>
#include <cstdint>
#include <memory_resource>
#include <span>
#include <vector>

namespace rangefit {

// Where to look, in the cloud's frame: a ball around the expected entrance, split by the CAD
// axis and plane into the expected wall's points and the rest.
struct RegionShape {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();         // expected entrance, mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();          // CAD axis, unit
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();  // CAD plane normal, unit, toward sensor
  double roi_radius = 0.0;                                  // region: within this of the centre, mm
  double pool_radius = 0.0;  // read (normal neighbours): within this, mm (>= roi_radius)
  // Near the wall: deeper than below_margin under the CAD plane and within rho_lo..rho_hi of
  // the CAD axis (0.8 rho_lo: the CAD axis may be off).
  double rho_lo = 0.0, rho_hi = 0.0, below_margin = 0.0;
  bool split = true;  // false: no near_wall / near_plane / other lists
};

struct BoreRegion {
  explicit BoreRegion(std::pmr::memory_resource* mr = std::pmr::get_default_resource())
      : points(mr), source(mr), roi(mr), near_wall(mr), near_plane(mr), other(mr) {}
  std::pmr::vector<Eigen::Vector3d> points;  // every point read within pool_radius, mm
  std::pmr::vector<std::uint32_t> source;    // cloud index of each of points
  std::pmr::vector<std::uint32_t> roi;       // indices into points within roi_radius
  // The region split (RegionShape::split): near the expected wall, near the plane (not below
  // it), and the rest (a pipe's other wall, a neighbouring bore, a blind bore's bottom).
  std::pmr::vector<std::uint32_t> near_wall, near_plane, other;
  std::size_t stride = 1;      // every stride-th scan point was read
  std::size_t non_finite = 0;  // NaN/Inf points among those read
};

// budget: region points aimed at (0: read every point). Deterministic. Buffers from `mr`.
BoreRegion select_region(std::span<const Eigen::Vector3d> cloud, const RegionShape& shape,
                         std::size_t budget,
                         std::pmr::memory_resource* mr = std::pmr::get_default_resource());

}  // namespace rangefit
