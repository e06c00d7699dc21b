#pragma once
// Inputs of the bore detection (thesis chapter 4): the CAD prior and every step's settings, with
// the thesis's values as defaults except where a measured improvement is marked "beyond".

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "detect/bore/cylinder_lsf.hpp"
#include "detect/bore/cylinder_rsf.hpp"

namespace rangefit {

// The expected bore from the CAD model, in the cloud's frame.
struct BorePrior {
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero();  // expected entrance point, mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     // expected axis (either sign)
  double radius = 0.0;                                 // expected radius, mm
  // A thick-walled pipe's outer wall radius, mm (> radius); 0: a bore, no outer wall.
  double outer_radius = 0.0;
  // Normal of the surface around the bore; nullopt: the axis (a perpendicular bore).
  std::optional<Eigen::Vector3d> plane_normal;
  // Beyond the thesis (its ch. 7 future work): the model, when the bore is not a circular
  // cylinder (detect/bore_surface.hpp). At most one of:
  // a cone narrowing with depth, radius at the entrance, this half-angle, rad (a 90 deg
  // countersink: pi/4; a tapered hole: a few degrees); 0: no cone.
  double half_angle = 0.0;
  // With a cone: > 0, the cylindrical bore of this radius the cone ends in (a countersunk
  // hole), mm; 0: a pure cone.
  double cylinder_radius = 0.0;
  // > 0: an elliptic bore, radius the semi-axis along major_axis and this the other one, mm.
  double radius2 = 0.0;
  Eigen::Vector3d major_axis =
      Eigen::Vector3d::Zero();  // across the axis (its part along it drops)
};

// Which cylinder of a pipe to fit: the bore (concave, inner), the outer (convex) wall, or both.
enum class BoreWalls { kInner, kOuter, kBoth };

struct BoreOptions {
  // Beyond the thesis: cost bounded by what the answer needs, not by the point count. Normals
  // only on an evenly spread subset of the region (up to the budgets below; a small bore keeps
  // every point), their radius shrunk on dense scans to hold about normal_neighbours points, and
  // the refinement iterated on a spread sample of the band, then polished on every inlier.
  // false: the session-1 pipeline (every region point, R as set, full-band iterations), kept as
  // the benchmark's baseline.
  bool cost_bounded = true;
  // The region is read at the scan stride that leaves about this many of its points (a small
  // bore's region, within the budget, is read whole); 0: every point (detect/bore_region.hpp).
  std::size_t region_budget = 16000;
  std::size_t normal_wall_budget = 1200;  // normals near the expected wall (RSF needs ~1000)
  std::size_t normal_plane_budget = 400;  // normals elsewhere in the region (plane fit)
  double normal_neighbours = 40.0;        // points per normal patch aimed at on dense scans
  std::size_t refine_sample = 2000;       // band points the refinement iterates on
  // The final fit as Gauss-Newton steps that trim around every new estimate, and, on a region
  // read at a stride, with the skipped scan points next to each band point taken back, up to
  // about refine_budget points; false: one step on the band trimmed around the sample's fit
  // (the pipeline before; biased on a narrow arc).
  bool refine_full_resolution = true;
  std::size_t refine_budget = 10000;
  // Where those points leave the axis's offset poorly determined (its one-sigma above
  // refine_polish_offset: a narrow arc, whose offset across the arc trades against the radius,
  // and the entrance lies on that axis), refine_polish_steps more steps on every scan point of
  // the band, beyond the budget. 0: never.
  double refine_polish_offset = 0.0025;  // mm, half the 0.005 mm entrance goal
  int refine_polish_steps = 1;
  BoreWalls walls = BoreWalls::kInner;  // kOuter/kBoth: prior.outer_radius (else radius)
  // 4.1.1 region of interest and normals.
  double roi_radius_factor = 2.0;  // keep points within this * radius of the expected entrance
  double normal_keep = 1.0;        // share of ROI points that get a normal (thesis: 0.2)
  double normal_radius = 2.0;      // R, mm
  double normal_radius_max_share = 0.4;  // beyond: R at most this share of the CAD radius
  double max_centroid_offset = 0.1;      // eq. 4.4, share of R
  int min_neighbours = 6;
  // Normal orientation toward the sensor: position, else direction; neither: the plane normal.
  std::optional<Eigen::Vector3d> view_dir;
  std::optional<Eigen::Vector3d> sensor_position;
  // 4.1.2 Gaussian-image segmentation.
  double plane_angle_deg = 5.0;  // alpha < this to the plane normal (eq. 4.5)
  double wall_angle_deg = 5.0;   // |90 deg - beta| < this to the axis (eq. 4.6)
  double wall_band = 0.5;  // beyond: wall points beyond (1 + this) * radius of the CAD axis drop
  int min_plane_points = 20;
  int min_wall_points = 20;
  // 4.1.3 sequential cylinder fit.
  RsfOptions rsf;
  // 4.1.4 notches: wall points farther than this * r from the axis are dropped, then refit.
  double notch_ratio = 1.03;
  // Beyond the thesis: robust plane fit (drop points beyond this many rms, refit once).
  double plane_inlier_sigmas = 3.0;
  // Beyond the thesis: final geometric Levenberg-Marquardt fit (Huber) on the points within
  // refine_band of the RSF cylinder, then again without those beyond 3 robust sigmas.
  bool refine = true;
  double refine_band = 0.5;  // mm
  // Beyond: the refinement takes every region point in the band that lies deeper than
  // refine_plane_margin below the entrance plane; false: only the segmented wall points.
  bool refine_all_region_points = true;
  double refine_plane_margin = 0.2;  // mm (3.3 sigma of 0.06 mm noise on a sharp rim)
  double refine_above_wall = 0.5;    // share of R above the wall (98th pct height) still taken
  CylinderLsfOptions lsf;
  // A cone or elliptic bore (BorePrior::half_angle, radius2): the fit starts on the points
  // within shape_band of the CAD or RSF-seeded surface (a prior 0.3 mm and 2 deg off moves a
  // wall 10 mm deep by about 0.65 mm), then again on the full-resolution points within 3 robust
  // sigmas of that fit. A fit whose half-angle moves by more than shape_max_angle_change, radius
  // by more than 20 % or axis by more than 5 deg from its start is refused (kShapeFitFailed), as
  // is one whose inliers' rms residual exceeds shape_max_rms (the wrong model: a cone on a
  // plain bore fits its rim at ~0.4 mm rms, the right one 0.06 mm noise at about that).
  double shape_band = 0.8;                 // mm
  double shape_max_angle_change = 0.0873;  // rad (5 deg)
  double shape_max_rms = 0.2;              // mm
  std::uint64_t seed = 1;
};

}  // namespace rangefit
