#include "detect/learn/learn_split.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detect/common/pca.hpp"

namespace rangefit {

TwoPartSplit split_two_parts(std::span<const Eigen::Vector3d> points, std::size_t min_points) {
  TwoPartSplit out;
  if (points.size() < 2 * min_points || points.size() < 8) return out;
  const Eigen::Vector3d c = pca::centroid(points);
  const pca::Eigen3 e = pca::eigen_symmetric(pca::covariance(points, c));
  const Eigen::Vector3d axis = e.vectors.col(2);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector3d& p : points) {
    const double t = axis.dot(p - c);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  constexpr int kBins = 48;
  const double bin = (hi - lo) / kBins;
  if (!(bin > 0.0)) return out;
  // Width of each bin: the largest distance from the axis line (both sides of the moments'
  // other two directions summed as a range).
  std::vector<double> wmin(kBins * 2, std::numeric_limits<double>::infinity());
  std::vector<double> wmax(kBins * 2, -std::numeric_limits<double>::infinity());
  std::vector<int> count(kBins, 0);
  auto bin_of = [&](double t) {
    return std::clamp(static_cast<int>((t - lo) / bin), 0, kBins - 1);
  };
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - c;
    const int b = bin_of(axis.dot(d));
    ++count[b];
    for (int k = 0; k < 2; ++k) {
      const double u = e.vectors.col(k).dot(d);
      wmin[2 * b + k] = std::min(wmin[2 * b + k], u);
      wmax[2 * b + k] = std::max(wmax[2 * b + k], u);
    }
  }
  std::vector<double> width(kBins, 0.0);
  for (int b = 0; b < kBins; ++b) {
    if (count[b] == 0) continue;
    width[b] = std::max(wmax[2 * b] - wmin[2 * b], wmax[2 * b + 1] - wmin[2 * b + 1]);
  }
  // Two-level step fit: for each cut, the sum of squared deviations from each side's mean.
  double best = std::numeric_limits<double>::infinity();
  int cut = -1;
  for (int k = 2; k <= kBins - 2; ++k) {
    double cost = 0.0;
    for (int side = 0; side < 2; ++side) {
      const int b0 = side == 0 ? 0 : k, b1 = side == 0 ? k : kBins;
      double s = 0.0, s2 = 0.0;
      int n = 0;
      for (int b = b0; b < b1; ++b) {
        if (count[b] == 0) continue;
        s += width[b];
        s2 += width[b] * width[b];
        ++n;
      }
      if (n > 0) cost += s2 - s * s / n;
    }
    if (cost < best) {
      best = cost;
      cut = k;
    }
  }
  if (cut < 0) return out;
  const double t_cut = lo + cut * bin;
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    out.parts[axis.dot(points[i] - c) < t_cut ? 0 : 1].push_back(i);
  }
  out.ok = out.parts[0].size() >= min_points && out.parts[1].size() >= min_points;
  return out;
}

}  // namespace rangefit
