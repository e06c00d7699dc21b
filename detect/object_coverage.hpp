#pragma once
// Surface coverage of a posed part: the share of its visible surface that the scan actually
// holds points on. Beyond the thesis: M, I and S (eq. 5.2-5.4) only look at the points near a
// hypothesis, so a part posed against a fragment of another object (a flat box on a cylinder's
// cap, a shaft along an edge) fits well and is empty inside, yet most of the surface it claims
// has no points where the sensor would have seen them. Used to confirm a detection.

#include <Eigen/Geometry>
#include <optional>
#include <span>

#include "detect/kdtree.hpp"
#include "detect/pca.hpp"
#include "detect/range_image.hpp"
#include "detect/superquadric.hpp"

namespace rangefit {

struct CoverageOptions {
  int samples = 200;                         // surface samples (about half of them visible)
  double tolerance_mm = 3.0;                 // a sample is covered by a point this close
  double tolerance_of_min_size = 0.1;        // ... or this share of the smallest size, if larger
  std::optional<Eigen::Vector3d> viewpoint;  // sensor position; unset: see surface_coverage
  // Samples this close to the removed plane are not checked (their points went with it).
  std::optional<pca::Plane> removed_plane;
  double plane_margin_mm = 5.0;
  // The scan's first returns from the viewpoint (the whole scan, plane included): when set, the
  // samples the sensor saw past are counted too.
  const RangeImage* first_returns = nullptr;
};

struct SurfaceCoverage {
  double covered = 0.0;       // share of the visible samples with a scan point near them
  double seen_through = 0.0;  // share the sensor saw past (RayEvidence::kBehind): free space
};

// Shares in [0, 1] of the surface samples facing the viewpoint that have a point of `points`
// (indexed by `tree`) within the tolerance. Without a viewpoint the visible side is taken as
// the one towards the centroid of the points near the surface. Samples are spread over the
// surface evenly in the part's normalised coordinates (exactly even for a sphere). Both are 0
// when no sample is visible. Samples hidden behind other objects count as uncovered, so an
// occluded part scores lower: the threshold that uses this must allow for it.
// A part that is really there has few samples seen through (its silhouette's pose error); a
// part posed on a fragment of another object claims surface where the sensor saw the table.
SurfaceCoverage surface_coverage(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                                 std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                 const CoverageOptions& options = {});

}  // namespace rangefit
