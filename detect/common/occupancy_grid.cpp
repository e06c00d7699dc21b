#include "detect/common/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rangefit {

OccupancyGrid::OccupancyGrid(std::span<const Eigen::Vector3d> points, double cell_mm,
                             std::size_t max_cells) {
  if (!(cell_mm > 0.0) || !std::isfinite(cell_mm)) return;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d hi = -lo;
  std::size_t n = 0;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    ++n;
  }
  if (n == 0) return;
  const Eigen::Vector3d extent = hi - lo;
  if (!extent.allFinite()) return;
  // Grow the cell until the grid fits the budget (one bit per cell).
  double cell = cell_mm;
  const auto cells = [&](double c) {
    return (std::floor(extent.x() / c) + 1.0) * (std::floor(extent.y() / c) + 1.0) *
           (std::floor(extent.z() / c) + 1.0);
  };
  while (cells(cell) > static_cast<double>(max_cells)) cell *= 1.25;
  cell_ = cell;
  lo_ = lo;
  nx_ = static_cast<std::size_t>(std::floor(extent.x() / cell)) + 1;
  ny_ = static_cast<std::size_t>(std::floor(extent.y() / cell)) + 1;
  nz_ = static_cast<std::size_t>(std::floor(extent.z() / cell)) + 1;
  bits_.assign((nx_ * ny_ * nz_ + 63) / 64, 0);
  const auto blocks = [](std::size_t cells_along) {
    return ((cells_along - 1) >> kBlockShift) + 1;
  };
  bx_ = blocks(nx_), by_ = blocks(ny_);
  blocks_.assign(bx_ * by_ * blocks(nz_), 0);
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d q = (p - lo_) / cell_;
    const std::size_t i = std::min(nx_ - 1, static_cast<std::size_t>(q.x()));
    const std::size_t j = std::min(ny_ - 1, static_cast<std::size_t>(q.y()));
    const std::size_t k = std::min(nz_ - 1, static_cast<std::size_t>(q.z()));
    const std::size_t b = index(static_cast<std::int64_t>(i), static_cast<std::int64_t>(j),
                                static_cast<std::int64_t>(k));
    bits_[b >> 6] |= std::uint64_t{1} << (b & 63);
    blocks_[block(i, j, k)] = 1;
  }
}

std::optional<OccupancyGrid::Cell> OccupancyGrid::cell_of(const Eigen::Vector3d& p) const {
  if (bits_.empty() || !p.allFinite()) return std::nullopt;
  const Eigen::Vector3d q = (p - lo_) / cell_;
  if (q.x() < 0.0 || q.y() < 0.0 || q.z() < 0.0) return std::nullopt;
  const double fx = std::floor(q.x()), fy = std::floor(q.y()), fz = std::floor(q.z());
  if (fx >= static_cast<double>(nx_) || fy >= static_cast<double>(ny_) ||
      fz >= static_cast<double>(nz_)) {
    return std::nullopt;
  }
  return Cell{static_cast<std::size_t>(fx), static_cast<std::size_t>(fy),
              static_cast<std::size_t>(fz)};
}

bool OccupancyGrid::holds(const Cell& c) const {
  const std::size_t b = index(static_cast<std::int64_t>(c.i), static_cast<std::int64_t>(c.j),
                              static_cast<std::int64_t>(c.k));
  return (bits_[b >> 6] >> (b & 63)) & 1u;
}

bool OccupancyGrid::occupied(const Eigen::Vector3d& p) const {
  const std::optional<Cell> c = cell_of(p);
  return c && holds(*c);
}

double OccupancyGrid::first_hit(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                double skip_mm) const {
  if (bits_.empty()) return -1.0;
  // Clip the walk to the box: outside it there are no points.
  const Eigen::Vector3d hi =
      lo_ + cell_ * Eigen::Vector3d(static_cast<double>(nx_), static_cast<double>(ny_),
                                    static_cast<double>(nz_));
  const std::optional<BoxWalk> w = walk_in_box(from, to, skip_mm, lo_, hi);
  if (!w) return -1.0;
  const double step = 0.5 * cell_;
  const double block_mm = cell_ * static_cast<double>(1 << kBlockShift);
  double t = w->begin;
  while (t <= w->end) {
    const Eigen::Vector3d p = from + t * w->u;
    const std::optional<Cell> c = cell_of(p);
    if (!c || blocks_[block(c->i, c->j, c->k)]) {
      if (c && holds(*c)) return t;
      t += step;
      continue;
    }
    // An empty block: on to the first step at or past where the line leaves it (less a hair,
    // so that a step on its face is still looked at).
    const Eigen::Vector3d corner =
        lo_ + block_mm * Eigen::Vector3d(static_cast<double>(c->i >> kBlockShift),
                                         static_cast<double>(c->j >> kBlockShift),
                                         static_cast<double>(c->k >> kBlockShift));
    double leave = INFINITY;
    for (int a = 0; a < 3; ++a) {
      if (w->u[a] > 0.0) leave = std::min(leave, (corner[a] + block_mm - p[a]) / w->u[a]);
      if (w->u[a] < 0.0) leave = std::min(leave, (corner[a] - p[a]) / w->u[a]);
    }
    const double steps = std::ceil((leave - 1e-6 * cell_) / step);
    t += step * std::max(1.0, steps);
  }
  return -1.0;
}

std::optional<BoxWalk> walk_in_box(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                   double skip_mm, const Eigen::Vector3d& lo,
                                   const Eigen::Vector3d& hi) {
  const Eigen::Vector3d d = to - from;
  const double length = d.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
  BoxWalk w;
  w.u = d / length;
  w.begin = std::max(0.0, skip_mm), w.end = length;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(w.u[a]) < 1e-12) {
      if (from[a] < lo[a] || from[a] > hi[a]) return std::nullopt;
      continue;
    }
    double ta = (lo[a] - from[a]) / w.u[a], tb = (hi[a] - from[a]) / w.u[a];
    if (ta > tb) std::swap(ta, tb);
    w.begin = std::max(w.begin, ta);
    w.end = std::min(w.end, tb);
  }
  if (w.begin > w.end) return std::nullopt;
  return w;
}

}  // namespace rangefit
