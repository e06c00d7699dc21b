#pragma once
// One pose hypothesis of one superquadric part (thesis 5.1.2, "Hypotheses"): n RANSAC trials
// on small random patches, the best (smallest M) refined on the full-resolution neighbourhood,
// then scored for the verification (I and S, eq. 5.3-5.4). Used by detect_object().

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <span>

#include "detect/common/kdtree.hpp"
#include "detect/common/pca.hpp"
#include "detect/object/object_axial_slide.hpp"
#include "detect/object/object_detector.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit {

struct PartHypothesis {
  bool valid = false;  // false: no trial found enough neighbours
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
  PartScores scores;  // M, I, S (rank_sum filled by the vote)
};

struct PlacedPart;

// Everything a hypothesis needs to read; shared, read-only, by all worker threads.
struct HypothesisContext {
  std::span<const Eigen::Vector3d> points;  // the cloud after plane removal
  const KdTree* tree = nullptr;             // over `points`
  const ObjectDetectOptions* options = nullptr;
  // Candidates already judged and set aside: RANSAC seeds are not drawn among the points they
  // explain (G < 1 + refine_trim), so new hypotheses go elsewhere.
  std::span<const PlacedPart> seed_excluded;
  // RANSAC seeds are drawn among these points (indices into `points`) only; empty: all of them.
  std::span<const std::uint32_t> seed_pool;
  // The removed table plane, its normal towards the objects (rest_on_plane): RANSAC trials whose
  // part sinks into it by more than table_margin_mm() are not taken.
  std::optional<pca::Plane> table;
  double table_noise_mm = 0.0;  // the scan's range noise, as the table shows it
  // The part must rest on the table (a single-part model; ObjectDetectOptions::rest_on_plane):
  // RANSAC starts are slid onto it, and those that rest on it win over those that do not.
  bool rests_on_table = false;
};

// How far a part of this smallest size may reach through the table, or stand above it, and still
// rest on it: max(plane_margin, 10 % of the size) plus three times the table's noise. One margin
// for the RANSAC trials, the below-plane check and the rest-on-plane check.
double table_margin_mm(const ObjectDetectOptions& options, double min_size_mm, double noise_mm);

// How far the posed part's lowest point stands above the table (< 0: below it), by its own
// support (with its taper: a cone lying on its flank, standing on its base or hung from its
// apex); nullopt for pinched (eps > 1) parts, which it does not bound. Unlike sinks_by's
// inscribed ellipsoid, a box tilted onto an edge (the fig. 5.18 box, 20 deg) rests.
std::optional<double> lowest_above(const Superquadric& part, const Eigen::Isometry3d& T,
                                   const pca::Plane& table);

// The posed part stands square on the table: one of its axes within ~10 deg of the table's
// normal (on a face, a base or a flank).
bool stands_square(const Eigen::Isometry3d& T, const pca::Plane& table);

// How far a confirmed part's lowest point may be from the table (ObjectDetectOptions::
// rest_noise_factor): the scan's noise and a small share of the part's largest size (its tilt).
double rest_tolerance_mm(const ObjectDetectOptions& options, double max_size_mm, double noise_mm);

// Standard deviation (mm) of the height along `normal` of the posed part's point `q_part` (part
// frame) under the pose covariance `cov` (increments [dt world, w part frame], pose_fit.hpp):
// how well the points place the part's lowest point above the table.
double height_sigma_mm(const Eigen::Isometry3d& T_world_part, const Eigen::Vector3d& q_part,
                       const Eigen::Vector3d& normal, const Eigen::Matrix<double, 6, 6>& cov);

// A part already placed (another part of the same compound object): the points it explains
// (G < 1 + refine_trim of its own, or 1 + gamma without trimming) stay out of the refinement
// and scores of the part being fitted, so a head does not drag its shaft towards itself.
struct PlacedPart {
  Superquadric shape;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
};

// Deterministic: the same context, part and seed give the same hypothesis.
PartHypothesis generate_hypothesis(const HypothesisContext& ctx, const Superquadric& part,
                                   std::uint64_t seed);

// Iterative refinement on the full-resolution neighbourhood until M stops improving (5.1.2).
Eigen::Isometry3d refine_pose(const HypothesisContext& ctx, const Superquadric& part,
                              const Eigen::Isometry3d& T_world_part,
                              std::span<const PlacedPart> explained = {});

// The part slid along its flat-ended axes to where its wall's points end, as close to `prefer`
// (a shift along its own x, y, z, mm) as they allow (object_axial_slide.hpp): where its ends show
// no points, the refinement leaves it free along them.
Eigen::Isometry3d slide_pose(const HypothesisContext& ctx, const Superquadric& part,
                             const Eigen::Isometry3d& T_world_part, const Eigen::Vector3d& prefer,
                             std::span<const PlacedPart> explained = {});

// The same in two halves, for a part slid several ways from one pose: its wall's points gathered
// once (`explained`: points of the object's other parts, left out), then slid towards `prefer`.
WallRuns wall_at(const HypothesisContext& ctx, const Superquadric& part,
                 const Eigen::Isometry3d& T_world_part, std::span<const PlacedPart> explained = {});
Eigen::Isometry3d slide_pose(const HypothesisContext& ctx, const Superquadric& part,
                             const WallRuns& wall, const Eigen::Vector3d& prefer);

// M over the refinement selection, I and S over the neighbourhood within the verification radius.
PartScores verify_pose(const HypothesisContext& ctx, const Superquadric& part,
                       const Eigen::Isometry3d& T_world_part,
                       std::span<const PlacedPart> explained = {});

// How well the part's own size explains its points: the pose re-fitted with the size let free
// (size_fit.hpp: a scale across the part's axis and one along it, with their standard errors).
// A look-alike 4 % larger than the model wants ~1.04 whatever its point count; a part seen only
// on a plane face leaves its size free and gives no verdict.
struct SizeEvidence {
  bool determined = false;  // the points place at least one of the two scales
  bool across_open = true;  // ... but not the one across the part's axis (a cap's extent)
  double scale = 1.0;       // of those they place, the one farthest from 1 beyond its allowance
  double allowance = 0.0;   // size_deviation_sigmas x its standard error
  std::optional<double> across, along;  // each scale, where they place it
  double across_allowance = 0.0;
  // Robust spread of the distances from the surface of the points near it at the given pose,
  // mm (1.4826 median |d|: the sigma of the range noise for a part that is really there).
  double residual_mm = 0.0;
  // The pose's covariance as the points determine it (PoseFitResult::covariance of the fit at the
  // model's size); zero when there were too few points.
  Eigen::Matrix<double, 6, 6> pose_covariance = Eigen::Matrix<double, 6, 6>::Zero();
};
// The pose at the model's size fitted to the points' distances from its surface (size_fit.hpp)
// with robust weights: G - 1 weighs a box's narrow faces and rounded edges over the rest.
Eigen::Isometry3d polish_pose(const HypothesisContext& ctx, const Superquadric& part,
                              const Eigen::Isometry3d& T,
                              std::span<const PlacedPart> explained = {});

SizeEvidence size_evidence(const HypothesisContext& ctx, const Superquadric& part,
                           const Eigen::Isometry3d& T_world_part,
                           std::span<const PlacedPart> explained = {});

// The points near a part with flat ends fitted with its size let free (size_fit.hpp), and the
// same with the other cross-section: a box's round (eps2 1), a can's square (eps2 0.1). A can and
// a box of about the same size each fit the other's points at the scan's noise where little of
// them is seen, but where their side walls show, the wrong section's rms stands out.
struct SectionEvidence {
  bool asked = false;         // false: the part has no such section, or too few points
  double model_rms_mm = 0.0;  // the model's section
  double other_rms_mm = 0.0;  // the other one
};
SectionEvidence section_evidence(const HypothesisContext& ctx, const Superquadric& part,
                                 const Eigen::Isometry3d& T_world_part,
                                 std::span<const PlacedPart> explained = {});

// splitmix64: seeds per hypothesis from (seed, part, index), and the samplers' generator.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b);

}  // namespace rangefit
