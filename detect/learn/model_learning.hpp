#pragma once
// Learning an object model from a scan of the object alone (thesis ch. 6, "show the object
// once"; ch. 7): the dominant plane is removed, the object segmented (detect/learn_segment), and
// one tapered superquadric fitted to it (size, shape, taper and pose, detect/learn_fit: LM on
// the distance from the surface with a volume term against the single view's ambiguity, thesis 2.2)
// from several starts built from the moments (detect/learn_start); the best fit is kept. With two
// parts the two largest clusters are the parts when they do not touch and neither fit holds the
// other's centre. Otherwise the object is cut where its width steps (detect/learn_split); each
// of the best few cuts, and the points off a rough fit of its larger side, are tried as the two
// parts, and the try whose rough fits explain the object best is kept (a handle on the side of
// a mug: a one-sided view makes width steps of its own). Each side is fitted as one part, points
// reassigned to the nearer part and refitted (up to three times), a part whose foot floats just
// above the table grown down to it, a part whose points lie much farther off it than the other's
// learnt again from all its starts, and the link between them (eq. 5.5-5.6: angle between the
// z-axes, centre distance) measured.
//
// Several views of the object (already in one world frame) are fused by passing all their
// points: the fit's point budget is spread over the surface area (detect/spread_subset), so a
// surface seen twice weighs no more than one seen once, and the hidden side of one view is
// constrained by the other.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "detect/learn/learn_fit.hpp"
#include "detect/learn/learn_segment.hpp"
#include "detect/object/object_model.hpp"

namespace rangefit {

struct LearnOptions {
  int parts = 1;           // 1 or 2
  std::uint64_t seed = 1;  // of the plane removal's seed spread (the only sampled step)
  std::string name = "learnt";
  SegmentOptions segment;
  std::size_t fit_points = 1500;   // the final fits run on this many spread points at most
  std::size_t start_points = 400;  // the short fits of the starts on this many
  int start_iterations = 30;       // LM iterations of each start
  int iterations = 150;            // LM iterations of the final fits
  int kept_starts = 2;             // the best starts fitted to convergence
  // When the best of them leaves an rms distance above this (mm), all starts are fitted to
  // convergence; 0: retry_noise_factor x the removed plane's rms (the scan's noise), at least
  // 0.1 mm; negative: never.
  double retry_residual_mm = 0.0;
  double retry_noise_factor = 3.0;
  double volume_weight = 0.05;  // the fit's volume term (ShapeFitOptions; 0: none)
  // One part only: its end along the table normal held on the table (ShapeFitOptions; 0: off).
  double support_weight = 0.1;
  FitResidual residual = FitResidual::kDistance;  // of the fits (ShapeFitOptions)
  // Of the rough fits that compare the cuts of a compound object into two parts: the radial
  // distance leads the few short fits from the moments into the parts' shapes more surely (on
  // the distance, 2 more of 20 two-view mugs lost their handle's shape to a wrong cut).
  FitResidual rough_residual = FitResidual::kRadial;
  bool fit_taper = true;
  double max_taper = 1.0;
  double visible_tolerance_mm = 0;  // 0: 2 x the fit's rms distance + the segmentation gap / 2
  int threads = 0;  // the starts' fits run on this many threads (0: all cores); same result
};

enum class LearnReason {
  kLearnt,
  kEmptyCloud,       // no points
  kNoObject,         // nothing left after the plane removal, or only clusters below min_points
  kTooFewPoints,     // the object (or a part of it) has too few points to fit
  kInvalidOptions,   // parts not 1 or 2, non-positive counts
  kNonFinitePoints,  // a NaN or infinite coordinate in the input
  kAllAtOnePoint,    // the points (or the object's) span no extent: all the same point
  kCollinear,        // the points (or the object's) lie on a line: no surface to fit
  // Two parts asked for, but no cut of the object leaves two parts of which neither holds the
  // other's centre: the second part is hidden in this view (a mug's handle behind its body).
  kSecondPartNotSeen,
};
const char* to_string(LearnReason reason);

struct LearntPart {
  std::string name;
  Superquadric shape;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();  // in the scan
  std::size_t points = 0;      // object points assigned to this part
  double measure = 0.0;        // M, eq. 5.2, on those points
  double residual_mm = 0.0;    // rms distance of those points from the surface
  double visible_share = 0.0;  // share of the surface area with points near it
  int iterations = 0;          // of the final fit
};

struct LearnResult {
  LearnReason reason = LearnReason::kEmptyCloud;
  ObjectModel model;              // what the detectors read (io/object_model_file)
  std::vector<LearntPart> parts;  // in model order
  SegmentResult segment;          // the plane and the object's points
  int starts = 0;                 // fits started over all parts
  double total_ms = 0.0;
  bool learnt() const { return reason == LearnReason::kLearnt; }
};

// Fewer points than this (in the input, the object or a part) are too few to fit 13 parameters.
inline constexpr std::size_t kMinLearnPoints = 20;

LearnResult learn_model(std::span<const Eigen::Vector3d> points, const LearnOptions& options = {});

// Why these points cannot be fitted before any fit is tried: non-finite, fewer than
// kMinLearnPoints, all at one point or on a line (from the spread along their principal axes);
// kLearnt when they can.
LearnReason check_learn_points(std::span<const Eigen::Vector3d> points);

// One part fitted to given object points (no segmentation): the starts, the best kept_starts
// fitted to convergence, the best of those. `plane` closes the underside when given.
struct PartFit {
  ShapeFitResult fit;
  int starts = 0;
};
PartFit learn_part(std::span<const Eigen::Vector3d> object_points,
                   const std::optional<pca::Plane>& plane, const LearnOptions& options);

}  // namespace rangefit
