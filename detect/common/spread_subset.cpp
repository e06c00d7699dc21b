#include "detect/common/spread_subset.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit {
namespace {

// Marks the cube of each point in a dense bit grid over the box; keeps the first point per cube
// when `out` is given. Returns the occupied cube count. A dense grid: the box is a few dozen
// cubes across, a hash map would cost more than the pass; one bit per cube, so clearing it
// (up to 160^3 cubes) costs a memset of 0.5 MB, not 4 MB.
std::size_t occupy(std::span<const Eigen::Vector3d> points, std::span<const std::uint32_t> indices,
                   const Eigen::Vector3d& lo, double cell, int n, std::pmr::vector<std::uint64_t>& grid,
                   std::pmr::vector<std::uint32_t>* out, std::size_t stride = 1) {
  const std::size_t cubes = static_cast<std::size_t>(n) * n * n;
  grid.assign((cubes + 63) / 64, 0);
  const double inv = 1.0 / cell;
  std::size_t occupied = 0;
  for (std::size_t k = 0; k < indices.size(); k += stride) {
    const std::uint32_t i = indices[k];
    const Eigen::Vector3d q = (points[i] - lo) * inv;
    const int x = static_cast<int>(q.x()), y = static_cast<int>(q.y()), z = static_cast<int>(q.z());
    if (!(q.minCoeff() >= 0.0) || x >= n || y >= n || z >= n) continue;
    const std::size_t c = (static_cast<std::size_t>(x) * n + y) * n + z;
    std::uint64_t& word = grid[c / 64];
    const std::uint64_t bit = std::uint64_t{1} << (c % 64);
    if (word & bit) continue;
    word |= bit;
    ++occupied;
    if (out) out->push_back(i);
  }
  return occupied;
}

}  // namespace

SpreadSubset spread_subset(std::span<const Eigen::Vector3d> points,
                           std::span<const std::uint32_t> indices, const Eigen::Vector3d& centre,
                           double half, std::size_t target, std::pmr::memory_resource* mr) {
  SpreadSubset s{std::pmr::vector<std::uint32_t>(mr)};
  if (indices.size() <= target || !(half > 0.0) || target == 0) {
    s.indices.assign(indices.begin(), indices.end());
    return s;
  }
  const Eigen::Vector3d lo = centre - Eigen::Vector3d::Constant(half);
  std::pmr::vector<std::uint64_t> grid(mr);
  // Probe at 32 cubes across: the occupied count measures the surface area, from which the cube
  // size for `target` cubes follows (occupied cubes scale with area / cell^2).
  constexpr int kProbe = 32;
  const double probe = 2.0 * half / kProbe;
  // Every 4th point is enough to find the occupied probe cubes (hundreds of points each on a
  // dense scan; on a sparse one the count stays near the budget and every point is probed).
  const std::size_t stride = indices.size() > 8 * target ? 4 : 1;
  const std::size_t m = occupy(points, indices, lo, probe, kProbe, grid, nullptr, stride);
  s.area = static_cast<double>(m) * probe * probe;
  constexpr int kMaxCells = 160;  // 0.5 MB of flags at most
  const double cell =
      std::max(probe * std::sqrt(static_cast<double>(m) / static_cast<double>(target)),
               2.0 * half / kMaxCells);
  const int n = static_cast<int>(std::ceil(2.0 * half / cell)) + 1;
  s.indices.reserve(target + target / 2);
  occupy(points, indices, lo, cell, n, grid, &s.indices);
  s.cell = cell;
  // Stray points (outliers, ghosts) occupy cubes of their own and push the count past the
  // target: thin the kept ones evenly (scan order) back to it.
  if (s.indices.size() > target + target / 8) {
    const double keep = static_cast<double>(target) / static_cast<double>(s.indices.size());
    double acc = 0.0;
    std::size_t w = 0;
    for (const std::uint32_t i : s.indices) {
      acc += keep;
      if (acc >= 1.0) {
        acc -= 1.0;
        s.indices[w++] = i;
      }
    }
    s.indices.resize(w);
  }
  return s;
}

}  // namespace rangefit
