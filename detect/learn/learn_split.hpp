#pragma once
// The two-part decomposition of model learning: an object of two parts joined end to end or
// crosswise (a mallet's head on its shaft, a mug's handle on its side) changes its width
// abruptly along some direction. For each candidate direction the points are binned along it,
// each bin's width across it measured, and the cut put where a two-level step fits the width
// profile best (least squares over the cut position); the direction whose step leaves the least
// of the profile's variance unexplained is cut, and each side is one part.
//
// A one-sided view makes steps of its own (a standing cylinder seen from one side shows its
// wall on the near half and only its top on the far half), so the best few distinct cuts are
// returned, best step first, for the caller to tell apart by how well two parts fit them.
//
// The candidates are the points' principal axes and, when the table's normal is known, the
// normal and directions in the table's plane every 15 deg: a part attached to the side of a
// standing body (the mug's handle) need not lie along a principal axis of the whole, which a
// one-sided view skews.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace rangefit {

struct TwoPartSplit {
  std::array<std::vector<std::uint32_t>, 2> parts;  // indices into the points
  double unexplained = 1.0;  // share of the width profile's variance the step leaves
};

// At most `count` splits, best step first; two splits are distinct when their smaller sides
// share less than half of their points. Empty: too few points, or no cut leaves min_points on
// both sides.
std::vector<TwoPartSplit> split_two_parts(
    std::span<const Eigen::Vector3d> points, std::size_t min_points,
    const std::optional<Eigen::Vector3d>& table_normal = std::nullopt, int count = 1);

}  // namespace rangefit
