#pragma once
// The sequential random-sample cylinder fit, RSF (thesis 4.1.3): axis orientation from cross
// products of wall-normal pairs (eq. 4.7-4.9), radius from circumradii of random wall triangles
// projected along that axis (eq. 4.11-4.15), axis line by PCA of the axis points p + r n.

#include <Eigen/Core>
#include <cstdint>
#include <memory_resource>
#include <span>

namespace rangefit {

// An infinite cylinder: a point on the axis, the unit axis direction and the radius (mm).
struct Cylinder {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
};

// Perpendicular distance of p from the cylinder's axis line (eq. 4.16).
double axis_distance(const Cylinder& c, const Eigen::Vector3d& p);

enum class RadiusEstimator {
  kMean,         // the thesis, eq. 4.15: biased high on partial noisy arcs
  kMedian,       // robust to the heavy upper tail of circumradii
  kTrimmedMean,  // mean of the central (1 - 2 trim) share
};

struct RsfOptions {
  int axis_samples = 1000;           // cross products averaged (eq. 4.7)
  double min_pair_angle_deg = 15.0;  // gamma lower bound (eq. 4.9)
  double max_pair_angle_deg = 75.0;  // gamma upper bound (eq. 4.9)
  int radius_samples = 1000;         // circumradii averaged (eq. 4.15)
  double min_area_factor = 0.1;      // triangle area > factor * pi * r_cad^2 (eq. 4.14)
  RadiusEstimator radius_estimator = RadiusEstimator::kMedian;
  double trim_fraction = 0.25;    // kTrimmedMean: share cut at each end
  int max_draws_per_sample = 40;  // give up after this many rejected draws per sample
  // Beyond the thesis: draw triangle vertices from the three thirds of the arc (by azimuth
  // about the prior axis); the area limit is halved while fewer than a quarter of the
  // samples pass it (narrow fragments).
  bool stratified_triangles = true;
  // Beyond the thesis: cluster the axis points around the CAD axis (mean shift) before the line
  // fit, so a neighbouring bore's or an outer cylinder's normals cannot pull the axis line.
  bool cluster_axis_points = true;
  double cluster_window_factor = 0.3;  // mean-shift window radius as a share of the radius
};

enum class RsfStatus { kOk, kTooFewPoints, kNoAxisPairs, kNoTriangles, kDegenerateAxis };
const char* to_string(RsfStatus s);

struct RsfResult {
  RsfStatus status = RsfStatus::kTooFewPoints;
  Cylinder cylinder;
  Eigen::Vector3d axis_from_pairs = Eigen::Vector3d::UnitZ();  // u of eq. 4.7
  int axis_pairs = 0;                                          // accepted normal pairs
  int triangles = 0;                                           // accepted triangles
  int axis_points_used = 0;                                    // axis points in the final line fit
};

// points/normals: the segmented wall (normals unit, toward the axis). prior_axis orients the
// hemisphere of the cross products and the result; prior_point seeds the axis-point clustering
// (a point on or near the expected axis); expected_radius scales the area constraint. The
// fit's buffers come from `mr`.
RsfResult fit_cylinder_rsf(std::span<const Eigen::Vector3d> points,
                           std::span<const Eigen::Vector3d> normals,
                           const Eigen::Vector3d& prior_axis, const Eigen::Vector3d& prior_point,
                           double expected_radius, const RsfOptions& options, std::uint64_t seed,
                           std::pmr::memory_resource* mr = std::pmr::get_default_resource());

}  // namespace rangefit
