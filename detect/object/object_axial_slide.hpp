#pragma once
// Where a part with flat ends sits along its axis when its ends show no points. Beyond the
// thesis: a cylinder or box whose flat faces face along the sweep (or away from the camera) is
// seen only on its side walls, and the pose fit (eq. 5.1) leaves it free to slide along them:
// wall points past a cap have large G and fall out of the trimmed refinement band, wall points
// short of a cap cost nothing. So a mallet's head came out 4 mm short of its wall's end, and a
// shaft 3-4 mm off along its axis. The wall's points tell where the part ends: the part is slid
// along the axis, as little as possible, until the contiguous run of its wall points lies within
// its length. A wall longer than the part (a longer look-alike) is left alone: that is the
// continuation check's evidence (object_continuation.hpp), not to be explained away here.
//
// Asked along z for eps1 <= 0.5 (the side wall is straight along the axis) and, when eps2 <=
// 0.5 too (a box), along x and y as well. Tapered parts are not asked. The detector slides the
// parts of a compound object after their joint refinement (object_detector.cpp); single parts
// are judged as fitted (sliding them every refinement cost two cylinders and two boxes of the
// varied tuning scenes, slid onto a run of a longer can's wall that a shadow cut short).

#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "detect/common/kdtree.hpp"
#include "detect/common/pca.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit {

struct AxialSlideOptions {
  double reach = 0.25;   // wall points are looked for up to this share of the size past an end
  double band_mm = 1.0;  // a point is on the wall within this distance (the scan's noise)
  // A gap along the axis wider than this share of the part's size ends the wall's run (a
  // neighbouring object's coplanar face farther on is not the wall). At 0.1 a box's face 11 mm
  // past a 240 mm shaft's cap carried its run on and held it 7.5 mm off (two-camera mallet
  // tuning seed 377); at 0.05 the tuning and held-out scenes lost no run to a gap.
  double max_gap_share = 0.05;
  int min_wall_points = 10;  // fewer wall points within the part: no verdict
  // Along the part's own axis its wall is a band around the axis: a wall point whose
  // neighbours within sector_window_mm along the axis lie in fewer than min_wall_sectors of
  // wall_sectors equal sectors around it is not on the wall. Another object's surface crossing
  // the wall's extension past the part's end leaves a line there (one sector) that would carry
  // the run on.
  int wall_sectors = 16;  // at most 64
  int min_wall_sectors = 3;
  double sector_window_mm = 1.5;
  // Points this close to the removed table (normal towards the objects) are not asked: the table
  // touches a lying part's wall along its whole extended length.
  std::optional<pca::Plane> table;
  double table_margin_mm = 5.0;
  std::size_t max_points = 6000;  // even subsample of the neighbourhood
  // The shift along the part's x, y, z (mm) other evidence asks for (a compound part's link to
  // its sibling): taken as far as the wall's run allows. Zero: move as little as possible.
  Eigen::Vector3d prefer = Eigen::Vector3d::Zero();
};

// The pose slid along the part's axes to where its wall's points end (T itself when they give no
// reason to move), or as close to options.prefer as the wall's run allows. `skip`: points explained
// by other parts of the same object (may be empty).
Eigen::Isometry3d slide_to_wall(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                                std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                const AxialSlideOptions& options = {},
                                const std::function<bool(const Eigen::Vector3d&)>& skip = {});

// The same in two halves. The wall's points of a part at one pose, by the axes it may slide
// along: their coordinates along each axis, sorted (along z only where the wall surrounds the
// axis; empty along an axis not asked). Gathering them is the slide's cost; the shift for any
// `prefer` follows from them, so a part slid several ways from one pose gathers them once.
struct WallRuns {
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
  std::array<std::vector<double>, 3> along;
};

// The wall's points around pose T (the gathering half of slide_to_wall). `skip`: points explained
// by other parts of the same object (may be empty).
WallRuns wall_runs(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                   std::span<const Eigen::Vector3d> points, const KdTree& tree,
                   const AxialSlideOptions& options = {},
                   const std::function<bool(const Eigen::Vector3d&)>& skip = {});

// The pose the runs were gathered at, slid as far as they allow towards options.prefer (the
// gathering options are not read again).
Eigen::Isometry3d slide_to_wall(const Superquadric& sq, const WallRuns& runs,
                                const AxialSlideOptions& options = {});

}  // namespace rangefit
