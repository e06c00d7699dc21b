#include "detect/object/object_axial_slide.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace rangefit {
namespace {

// A part stretched by this factor along one axis stands for its wall extended without end: for
// eps <= 0.5 its G along that axis is (z / (10 a))^(2 / eps) <= 1.25^4 / 10^4 within the reach.
constexpr double kEndless = 10.0;

// The shift along one axis of half size `a` that puts the contiguous run of wall coordinates
// `u` (sorted) with the most points within the part inside [-a, a], closest to `prefer`; 0 when
// no shift does. Runs end at gaps wider than max_gap_share x a: a few stray points within the
// part (another object's, a shadow's edge) are not its wall.
double shift_for(const std::vector<double>& u, double a, double prefer,
                 const AxialSlideOptions& o) {
  const double gap = o.max_gap_share * a;
  std::ptrdiff_t best_within = 0;
  std::size_t lo = 0, hi = 0;
  for (std::size_t begin = 0; begin < u.size();) {
    std::size_t end = begin + 1;  // the run is [begin, end)
    while (end < u.size() && u[end] - u[end - 1] <= gap) ++end;
    const auto first = std::lower_bound(u.begin() + static_cast<std::ptrdiff_t>(begin),
                                        u.begin() + static_cast<std::ptrdiff_t>(end), -a);
    const auto last = std::upper_bound(first, u.begin() + static_cast<std::ptrdiff_t>(end), a);
    if (last - first > best_within) best_within = last - first, lo = begin, hi = end - 1;
    begin = end;
  }
  if (best_within < o.min_wall_points) return 0.0;
  const double s_min = u[hi] - a, s_max = u[lo] + a;  // shifts that contain [u[lo], u[hi]]
  if (s_min > s_max) return 0.0;                      // the wall is longer than the part
  return std::clamp(prefer, s_min, s_max);
}

// The wall points' coordinates along the part's z-axis, sorted, kept where the points within
// sector_window_mm of them along the axis lie in at least min_wall_sectors sectors around it.
// `around`: each point's angle about the axis in the cross-section's normalised coordinates
// (x / a1, y / a2), so that a box's four faces span equal sectors.
std::vector<double> around_the_axis(const std::vector<double>& u, const std::vector<double>& around,
                                    const AxialSlideOptions& o) {
  const int sectors = std::clamp(o.wall_sectors, 1, 64);
  std::vector<std::pair<double, int>> zs;  // (z, sector), by z
  zs.reserve(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double turn = (around[i] + std::numbers::pi) / (2.0 * std::numbers::pi);
    zs.emplace_back(u[i], std::clamp(static_cast<int>(turn * sectors), 0, sectors - 1));
  }
  std::sort(zs.begin(), zs.end());
  std::array<int, 64> in_window{};  // points per sector within the window
  int distinct = 0;
  std::vector<double> out;
  for (std::size_t i = 0, lo = 0, hi = 0; i < zs.size(); ++i) {
    for (; hi < zs.size() && zs[hi].first <= zs[i].first + o.sector_window_mm; ++hi) {
      distinct += in_window[static_cast<std::size_t>(zs[hi].second)]++ == 0;
    }
    for (; zs[lo].first < zs[i].first - o.sector_window_mm; ++lo) {
      distinct -= --in_window[static_cast<std::size_t>(zs[lo].second)] == 0;
    }
    if (distinct >= o.min_wall_sectors) out.push_back(zs[i].first);
  }
  return out;
}

}  // namespace

WallRuns wall_runs(const Superquadric& sq, const Eigen::Isometry3d& T,
                   std::span<const Eigen::Vector3d> points, const KdTree& tree,
                   const AxialSlideOptions& o,
                   const std::function<bool(const Eigen::Vector3d&)>& skip) {
  WallRuns runs;
  runs.T_world_part = T;
  if (!sq.valid() || points.empty() || sq.kx != 0.0 || sq.ky != 0.0 || sq.eps1 > kFlatExponent) {
    return runs;
  }
  std::vector<int> axes{2};
  if (sq.eps2 <= kFlatExponent) axes = {2, 0, 1};
  const Eigen::Vector3d size(sq.a1, sq.a2, sq.a3);
  const double r = 1.0 + o.reach;
  std::vector<std::uint32_t> nbr;
  tree.radius_search(T.translation(), r * size.norm() + o.band_mm, nbr);
  const double stride =
      std::max(1.0, static_cast<double>(nbr.size()) / static_cast<double>(o.max_points));
  std::vector<Eigen::Vector3d> q;  // part frame
  for (double f = 0.0; f < static_cast<double>(nbr.size()); f += stride) {
    const Eigen::Vector3d& p = points[nbr[static_cast<std::size_t>(f)]];
    if (o.table && o.table->normal.dot(p - o.table->point) < o.table_margin_mm) continue;
    if (skip && skip(p)) continue;
    q.push_back(T.inverse() * p);
  }
  for (int k : axes) {
    Superquadric endless = sq;
    (k == 0 ? endless.a1 : k == 1 ? endless.a2 : endless.a3) *= kEndless;
    const SuperquadricMetric wall(endless);
    const double a = size[k];
    std::vector<double>& u = runs.along[static_cast<std::size_t>(k)];
    std::vector<double> around;
    for (const Eigen::Vector3d& x : q) {
      if (std::abs(x[k]) > r * a) continue;
      // On the wall along axis k: near the endless part's surface, and not on one of the other
      // axes' faces far out (for a box, the faces across k are walls too, within their size).
      if (std::abs(surface_distance(wall, x)) > o.band_mm) continue;
      u.push_back(x[k]);
      if (k == 2) around.push_back(std::atan2(x.y() / sq.a2, x.x() / sq.a1));
    }
    if (k == 2) {
      u = around_the_axis(u, around, o);
    } else {
      std::sort(u.begin(), u.end());
    }
  }
  return runs;
}

Eigen::Isometry3d slide_to_wall(const Superquadric& sq, const WallRuns& runs,
                                const AxialSlideOptions& o) {
  const Eigen::Vector3d size(sq.a1, sq.a2, sq.a3);
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const std::vector<double>& u = runs.along[static_cast<std::size_t>(k)];
    if (!u.empty()) shift[k] = shift_for(u, size[k], o.prefer[k], o);
  }
  if (shift.isZero()) return runs.T_world_part;
  Eigen::Isometry3d out = runs.T_world_part;
  out.translation() += runs.T_world_part.linear() * shift;
  return out;
}

Eigen::Isometry3d slide_to_wall(const Superquadric& sq, const Eigen::Isometry3d& T,
                                std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                const AxialSlideOptions& o,
                                const std::function<bool(const Eigen::Vector3d&)>& skip) {
  return slide_to_wall(sq, wall_runs(sq, T, points, tree, o, skip), o);
}

}  // namespace rangefit
