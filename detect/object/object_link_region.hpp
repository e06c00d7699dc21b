#pragma once
// Where a compound model's link puts one part, given its sibling's pose: the scan points such a
// part could lie on. Beyond the thesis (5.1.3 checks the links only in the vote, after every
// part was searched over the whole scan): in clutter a part whose RANSAC seeds all fell on a wall
// or a look-alike is never hypothesised, though its found sibling says where it must be. The
// detector seeds further hypotheses of that part here (object_detector.cpp).
//
// The link (angle, distance d, bearings) puts the part's centre on a circle around the sibling's
// axis, d cos(b) along it either way and d sin(b) out (b: the sibling's bearing); the part's own
// bearing, when it is (nearly) 0, aims its axis at the sibling's centre. So a mallet's head is
// near one of two points on its shaft's line, and a shaft lies in a flat ring in its head's
// middle plane. Without bearings (older model files) the centre may be anywhere on a sphere of
// radius d.

#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <vector>

#include "detect/common/kdtree.hpp"
#include "detect/object/object_model.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit {

// Indices (ascending) of the points within margin_mm of the part (taken as a capsule along its
// z-axis where the link sets the axis, a ball of its bounding radius where it does not) at any
// of the places the link allows; `first`: the part is the link's first part.
std::vector<std::uint32_t> link_region(const PartLink& link, bool first, const Superquadric& part,
                                       const Eigen::Isometry3d& T_world_sibling, double margin_mm,
                                       std::span<const Eigen::Vector3d> points, const KdTree& tree);

}  // namespace rangefit
