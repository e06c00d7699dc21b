#pragma once
// Which cells of space hold scan points: a dense bit grid over the scan's bounding box. It answers
// "what lies on the line of sight from this surface point to an eye?" for any eye, fixed or
// moving with the sweep (a stripe ranger's laser apex and camera), where a range image needs one
// fixed viewpoint. Used to tell the surface a posed part could have shown the scan from what was
// hidden (occluded by measured surface) and from where the sensor saw past it (free space).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace rangefit {

// A walk along the line from `from` towards `to`, clipped to the box [lo, hi] and started after
// `skip_mm`: the unit direction and the distances [begin, end] of the walk from `from`; nullopt
// for a degenerate line, or one that misses the box.
struct BoxWalk {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  double begin = 0.0, end = -1.0;
};
std::optional<BoxWalk> walk_in_box(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                   double skip_mm, const Eigen::Vector3d& lo,
                                   const Eigen::Vector3d& hi);

class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  // Cells of `cell_mm` (grown when the box would need more than `max_cells`). Non-finite
  // points are skipped.
  OccupancyGrid(std::span<const Eigen::Vector3d> points, double cell_mm,
                std::size_t max_cells = std::size_t{1} << 26);

  bool empty() const { return bits_.empty(); }
  double cell_mm() const { return cell_; }
  bool occupied(const Eigen::Vector3d& p) const;

  // Walks from `from` towards `to` (both world, mm), skipping the first `skip_mm`, and returns the
  // distance from `from` of the first occupied cell met, or a negative value when none is met
  // before `to` (or the box ends). Steps of half a cell: a surface of points at about the cell
  // spacing is not stepped over. The steps that fall in an empty block of cells are not taken
  // one by one: most of a line of sight to an eye crosses empty space above the scan.
  double first_hit(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double skip_mm) const;

 private:
  struct Cell {
    std::size_t i = 0, j = 0, k = 0;
  };
  std::optional<Cell> cell_of(const Eigen::Vector3d& p) const;  // nullopt: outside the grid
  bool holds(const Cell& c) const;                              // a scan point lies in it
  static constexpr int kBlockShift = 3;  // blocks of 8 x 8 x 8 cells
  std::size_t block(std::size_t i, std::size_t j, std::size_t k) const {  // of cell (i, j, k)
    return ((k >> kBlockShift) * by_ + (j >> kBlockShift)) * bx_ + (i >> kBlockShift);
  }
  std::size_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (static_cast<std::size_t>(k) * ny_ + static_cast<std::size_t>(j)) * nx_ +
           static_cast<std::size_t>(i);
  }
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  std::size_t nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<std::uint64_t> bits_;
  std::size_t bx_ = 0, by_ = 0;       // blocks along x and y
  std::vector<std::uint8_t> blocks_;  // per block: does any of its cells hold a point
};

}  // namespace rangefit
