#pragma once
// The two-part decomposition of model learning: an object of two parts joined end to end or
// crosswise (a mallet's head on its shaft) changes its width abruptly along its main axis. The
// points are binned along the largest central moment, each bin's width across it measured, and
// the cut put where a two-level step fits the width profile best (least squares over the cut
// position); each side is one part.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace rangefit {

struct TwoPartSplit {
  std::array<std::vector<std::uint32_t>, 2> parts;  // indices into the points
  bool ok = false;                                  // false: too few points or no step
};

TwoPartSplit split_two_parts(std::span<const Eigen::Vector3d> points, std::size_t min_points);

}  // namespace rangefit
