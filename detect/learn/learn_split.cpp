#include "detect/learn/learn_split.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "detect/common/pca.hpp"

namespace rangefit {
namespace {

constexpr int kBins = 48;

struct StepCut {
  double t_cut = 0.0;        // along the direction, from the centroid
  double unexplained = 1.0;  // the step fit's squared deviations over the profile's
  bool ok = false;
};

// The width profile along `axis` and the two-level step that fits it best. The width of a bin is
// the largest range of its points along four directions across the axis (45 deg apart), so it
// hardly depends on how the directions across are chosen.
StepCut best_step(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& axis) {
  StepCut out;
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  const std::array<Eigen::Vector3d, 4> across = {u, v, (u + v) / std::numbers::sqrt2,
                                                 (u - v) / std::numbers::sqrt2};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector3d& p : points) {
    const double t = axis.dot(p - c);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  const double bin = (hi - lo) / kBins;
  if (!(bin > 0.0)) return out;
  std::array<double, kBins * 4> wmin, wmax;
  wmin.fill(std::numeric_limits<double>::infinity());
  wmax.fill(-std::numeric_limits<double>::infinity());
  std::array<int, kBins> count{};
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - c;
    const int b = std::clamp(static_cast<int>((axis.dot(d) - lo) / bin), 0, kBins - 1);
    ++count[b];
    for (int k = 0; k < 4; ++k) {
      const double w = across[k].dot(d);
      wmin[4 * b + k] = std::min(wmin[4 * b + k], w);
      wmax[4 * b + k] = std::max(wmax[4 * b + k], w);
    }
  }
  std::array<double, kBins> width{};
  double s = 0.0, s2 = 0.0;
  int n = 0;
  for (int b = 0; b < kBins; ++b) {
    if (count[b] == 0) continue;
    for (int k = 0; k < 4; ++k) width[b] = std::max(width[b], wmax[4 * b + k] - wmin[4 * b + k]);
    s += width[b];
    s2 += width[b] * width[b];
    ++n;
  }
  const double total = s2 - s * s / std::max(n, 1);
  if (!(total > 0.0)) return out;
  // Two-level step fit: for each cut, the sum of squared deviations from each side's mean.
  double best = std::numeric_limits<double>::infinity();
  int cut = -1;
  for (int k = 2; k <= kBins - 2; ++k) {
    double cost = 0.0;
    for (int side = 0; side < 2; ++side) {
      const int b0 = side == 0 ? 0 : k, b1 = side == 0 ? k : kBins;
      double ss = 0.0, ss2 = 0.0;
      int m = 0;
      for (int b = b0; b < b1; ++b) {
        if (count[b] == 0) continue;
        ss += width[b];
        ss2 += width[b] * width[b];
        ++m;
      }
      if (m > 0) cost += ss2 - ss * ss / m;
    }
    if (cost < best) {
      best = cost;
      cut = k;
    }
  }
  if (cut < 0) return out;
  out.t_cut = lo + cut * bin;
  out.unexplained = best / total;
  out.ok = true;
  return out;
}

// The side with fewer points, as a membership mask, and its size.
struct SmallerSide {
  std::vector<char> mask;
  std::size_t size = 0;
};
SmallerSide smaller_side(const TwoPartSplit& s, std::size_t n) {
  SmallerSide out{std::vector<char>(n, 0), std::min(s.parts[0].size(), s.parts[1].size())};
  for (std::uint32_t i : s.parts[s.parts[0].size() <= s.parts[1].size() ? 0 : 1]) out.mask[i] = 1;
  return out;
}

}  // namespace

std::vector<TwoPartSplit> split_two_parts(std::span<const Eigen::Vector3d> points,
                                          std::size_t min_points,
                                          const std::optional<Eigen::Vector3d>& table_normal,
                                          int count) {
  std::vector<TwoPartSplit> out;
  if (points.size() < 2 * min_points || points.size() < 8 || count < 1) return out;
  const Eigen::Vector3d c = pca::centroid(points);
  const pca::Eigen3 e = pca::eigen_symmetric(pca::covariance(points, c));
  std::vector<Eigen::Vector3d> directions = {e.vectors.col(2), e.vectors.col(1), e.vectors.col(0)};
  if (table_normal && table_normal->norm() > 0.0) {
    const Eigen::Vector3d n = table_normal->normalized();
    const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
    directions.push_back(n);
    constexpr int kInPlane = 12;  // every 15 deg over half a turn
    for (int k = 0; k < kInPlane; ++k) {
      const double a = std::numbers::pi * k / kInPlane;
      directions.push_back(std::cos(a) * u + std::sin(a) * v);
    }
  }
  // Every direction's best cut that leaves min_points on both sides, best step first.
  std::vector<TwoPartSplit> cuts;
  for (const Eigen::Vector3d& axis : directions) {
    const StepCut s = best_step(points, c, axis);
    if (!s.ok) continue;
    TwoPartSplit split;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
      split.parts[axis.dot(points[i] - c) < s.t_cut ? 0 : 1].push_back(i);
    }
    if (split.parts[0].size() < min_points || split.parts[1].size() < min_points) continue;
    split.unexplained = s.unexplained;
    cuts.push_back(std::move(split));
  }
  std::stable_sort(cuts.begin(), cuts.end(), [](const TwoPartSplit& a, const TwoPartSplit& b) {
    return a.unexplained < b.unexplained;
  });
  std::vector<SmallerSide> taken;
  for (TwoPartSplit& cut : cuts) {
    if (static_cast<int>(out.size()) == count) break;
    SmallerSide side = smaller_side(cut, points.size());
    const auto shares_half = [&](const SmallerSide& t) {
      std::size_t shared = 0;
      for (std::size_t i = 0; i < side.mask.size(); ++i) shared += side.mask[i] & t.mask[i];
      return 2 * shared >= std::min(side.size, t.size);
    };
    if (std::any_of(taken.begin(), taken.end(), shares_half)) continue;
    taken.push_back(std::move(side));
    out.push_back(std::move(cut));
  }
  return out;
}

}  // namespace rangefit
