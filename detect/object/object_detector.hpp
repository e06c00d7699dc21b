#pragma once
// Superquadric object detection in a single-view scan (thesis ch. 5): dominant plane removal,
// m pose hypotheses per part, each the best of n RANSAC trials refined on the full-resolution
// neighbourhood, verified by a ranked vote over M, I and S (eq. 5.2-5.4) and, for compound
// models, over the link deviations A and D (eq. 5.5-5.6).
//
// Beyond the thesis: hypotheses run on all cores in fixed batches, each with its own seed, so
// the result depends only on options.seed and not on thread timing; the search stops early once
// the leading hypothesis has been found again by independent hypotheses; several instances of
// the object can be returned without duplicates; and a part is only confirmed when the scan
// covers the surface this sensor could have measured of it, it claims no surface where the
// sensor saw past it (free space, detect/object_coverage.hpp), and its points want the model's
// size (so a look-alike a few per cent larger or smaller is not taken for it).

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "detect/object/object_model.hpp"
#include "detect/common/plane_removal.hpp"
#include "detect/common/sensor_view.hpp"

namespace rangefit {

// How the final pose is chosen from the hypotheses (thesis 5.2.2, table 5.5).
enum class Selection {
  kMeasure,     // smallest M only (methods A and B)
  kRankedVote,  // lowest rank sum over M, I and S (methods C and D, and ours)
};

struct ObjectDetectOptions {
  int hypotheses = 32;           // m, at most: single-part models stop early once confirmed
  int compound_hypotheses = 18;  // m per part of compound models (always all of them)
  // ... and then, for each of a part's `linked_places` best places (distinct, seen as claimed)
  // with no hypothesis of a sibling where their link puts it, this many more of that sibling,
  // seeded there (object_link_region.hpp): in clutter a head whose seeds all fell on a wall is
  // found again from its shaft.
  int linked_places = 3;
  int linked_hypotheses = 4;
  int trials = 10;               // n RANSAC trials per hypothesis
  int sample_points = 30;        // points of each RANSAC sample (thesis: 20-50)
  int iterations = 20;           // LM iterations of each fit
  int init_iterations = 10;      // LM iterations of each of the moment-direction fits (5.1.2)
  int refine_rounds = 5;         // at most this many refinements "until M stops improving"
  std::size_t max_refine_points = 1500;  // even subsample of the neighbourhood per refinement
  bool refine_each_trial = false;        // method B/D: refine every trial, not only the best
  // Refinement uses only neighbourhood points with G < 1 + refine_trim (clutter and the remains of
  // other objects stay out of the least squares); 0 uses all of them as the thesis does.
  double refine_trim = 0.6;
  double gamma = 0.2;  // surface band of eq. 5.3-5.4
  // Confirmation (beyond the thesis, whose vote always returns its best hypothesis): a part is
  // only reported when it fits its points (M <= max_measure) and is not full of points (a
  // single-view scan sees surfaces, so I <= max_interior_ratio (I + S)). A scene without the
  // object then gives found() == false instead of the least bad misfit.
  double max_measure = 0.25;
  double max_interior_ratio = 0.2;
  std::size_t min_surface_points = 20;
  // And the scan holds points on this share of the surface the sensor could have measured of
  // the part (object_coverage.hpp: shadows, occlusion and the sweep's ends excluded); checked on
  // the vote's best candidates. With an unknown sensor the measurable surface is a guess that
  // includes shadows, so a lower share is asked for.
  double min_coverage = 0.6;
  double min_coverage_unknown_sensor = 0.4;
  // A compound object is held to min_coverage over all its parts' measurable surface together,
  // each part alone only to this share: the linked parts are the evidence, and one part partly
  // hidden (a mallet head under an overhang at 0.53, a shaft behind a wall at 0.50 on the varied
  // tuning scenes) no longer loses an object whose other part is fully seen.
  double min_coverage_compound_part = 0.4;
  // And at most this share of it lies where the sensor saw past it (free space). Rejects a part
  // posed on a fragment of a larger object.
  double max_seen_through = 0.05;
  // A compound object's parts are screened before they are combined (the vote's candidates are
  // only parts the scan shows where they claim surface), each hypothesis at its own pose, before
  // the parts are linked and refined together: the screen allows this many times
  // max_seen_through, and the object is held to max_seen_through itself when it is confirmed. At
  // the limit itself a true mallet head fitted a little off was set aside with all its hypotheses
  // (0.056 on pan-tilt tuning seed 133), and the mallet was lost.
  double compound_screen_slack = 1.5;
  // A single part rejected for space seen through is slid along its wall and turned about the
  // table's normal (a part posed off), unless at least this share of it lies where the sensor saw
  // past it: then it stands where nothing is, and moving it is not tried. On tuning 1..300 (box,
  // cylinder, cone; stripe and pan-tilt) 79 such moves were tried where the object was and 3
  // confirmed, none of them deciding a scene; 478 were tried on the object-free scenes.
  double max_seen_through_posed_off = 0.5;
  // And by each of its flat ends (a box, a can) whose side wall the scan shows farther in, at
  // most this share of the side wall it could have measured there has no scan points near it
  // (object_coverage.hpp open_end): a part fitted to a shorter look-alike lying along the sweep
  // reaches past its end. The true single parts confirmed on the varied tuning scenes had 0; a can
  // 7 % shorter lying along the sweep, fitted by the model, had 0.4.
  double max_open_end = 0.3;
  // The same for a part of a compound object, by its ends that face no sibling (a shaft's end at
  // its head is not asked), once the siblings are placed. Looser: a true mallet head of the
  // tuning scenes had 0.4 at 0.76 mm noise, a head slid along its axis onto a rod at the link's
  // distance 1.0.
  double max_open_end_compound = 0.6;
  // And by each flat cap's edge where the scan shows the cap farther in, at most this share of
  // the cap's rim it could have measured has no scan points near it (object_coverage.hpp
  // open_rim; its second scale only where the size across the axis is left open: a true tilted
  // can of a pinhole render, its size placed, showed 0.64 there and none at the first scale).
  // Single parts only. A standing box or can seen from above fits a narrower look-alike
  // by one corner or flank as well as itself, and the size fit, whose one scale across the axis
  // is tied by the height, may read the model's size. On the varied
  // tuning scenes (seeds 1-200) the true boxes and cans whose size was undetermined had at most
  // 0.12, look-alikes 9-20 % narrower fitted by the model 0.37-1.0; a box 6 % narrower, its size
  // read as 1.01, 0.33, and one 18 % narrower overhung by 9 mm, beyond the first scale, 0.56.
  double max_open_rim = 0.3;
  // And it shows the sensor at least this many of the coverage's surface samples, and this share
  // of those facing it (a part hidden behind others, under the table or inside a measured
  // object leaves too little to judge it by), and it does not reach farther than the table
  // margin through the removed plane (parts rest on the table, they do not sink into it). Grazed
  // samples with scan points on them count towards both (object_coverage.hpp grazed).
  int min_measurable_samples = 10;
  // Parts rest on the removed plane (the table): the lowest point of a single part, or of a
  // compound object's parts together, is within the table margin of it. Off for scenes of
  // stacked parts.
  bool rest_on_plane = true;
  double min_measurable_share = 0.4;
  // A single part mostly hidden (under an overhang, behind a wall) is still judged on a smaller
  // measurable share, down to this, when the scan covers at least full_coverage of what it could
  // have measured of it and saw past none of it. On the varied tuning scenes true cones and a box
  // under overhangs showed 0.30-0.36 of their facing surface, all of it covered; the misplaced
  // candidates rejected at such shares were covered to 0.17.
  double min_measurable_share_covered = 0.25;
  double full_coverage = 0.95;
  // The table margin of the RANSAC trials (a start on a small patch may sink into the table by
  // this much) and of the points the continuation leaves to the table: max(plane_margin, 10 % of
  // the part's smallest size) plus three times the table's noise (object_hypotheses.hpp
  // table_margin_mm).
  double plane_margin_mm = 5.0;
  // The table margin is also how far a confirmed part may sink into the table (the scenes of
  // the detector tests have parts a few millimetres into it). But it stands on the table: its
  // lowest point (or a compound object's; flat faces' rounded edges taken as sharp) is no higher
  // above it than rest_noise_factor x the table's noise plus rest_size_share of its largest size
  // (rest_tolerance_mm). The true parts of the varied tuning scenes rest to within 0.25 mm, but
  // the fig. 5.18 box (table 5.3 pose) is fitted up to 2.5 mm above the table; look-alikes 4-6 %
  // taller fitted to the model by their tops stood 4.3-5.8 mm off at 0.6-0.8 mm noise.
  double rest_noise_factor = 2.0;
  double rest_size_share = 0.06;
  // And a confirmed part sinks into the table by no more than its own points allow: sink_floor_mm
  // plus sink_noise_factor x the table's noise plus sink_sigma_factor x the standard deviation of
  // its lowest point's height under the pose covariance of its fit (the LM's s^2 (J^T J)^-1). A
  // part whose top and sides are seen is placed to a few hundredths of a millimetre, so a
  // look-alike a few per cent shorter, fitted by its top, sinks deeper than that; a part whose
  // points leave its height open (only its side seen) is held only to the table margin. A
  // compound object is held to it by at least one of its parts.
  double sink_floor_mm = 1.0;
  double sink_noise_factor = 2.0;
  double sink_sigma_factor = 3.0;
  // And, where its points determine it, the size the points want is the model's within this
  // share (object_hypotheses.hpp size_evidence): a sphere 4 % larger or smaller is not it; a box
  // or a cone seen from one side places its size to about 2 %. A tapered part is allowed
  // size_deviation_sigmas standard errors of the scale (the fit's, at most 0.005) more: its flank
  // alone trades width for height (a cone under an overhang seen at 0.6-0.9 mm noise on its
  // lower flank only wanted a thinner, taller cone, 3.3-4.8 % off at standard errors of
  // 0.3-0.5 %), and the look-alike cones of the tuning scenes stood 12-500 standard errors off.
  // Boxes and cans are not: the same allowance let two look-alike boxes 4-7 % larger through.
  double max_size_deviation = 0.03;
  double size_deviation_sigmas = 3.0;
  // And its points lie on its surface as closely as the scan's noise allows: the robust spread
  // of their distances from it (mm) is at most residual_noise_factor x the noise of the removed
  // plane plus max_residual_floor_mm (a part fitted across fragments of other objects is not).
  double residual_noise_factor = 2.0;
  double max_residual_floor_mm = 0.3;
  // And little of the scan carries on past its flat faces (object_continuation.hpp): the points
  // outside it on one of its faces extended by up to 25 % (farther at high noise), as a share of
  // its surface points (at most 0.003 on the true objects of the tuning scenes, 0.013-0.16 on
  // longer look-alikes).
  // Rejects a part posed on one end of a longer or wider look-alike.
  double max_continuation = 0.01;
  // And a single part with flat ends and a square (a box) or round (a can) cross-section fits its
  // points at least about as well as the other cross-section does: its size let free, the rms of
  // their distances from it is at most max_section_ratio x that of the other's, its size let free
  // as well (object_hypotheses.hpp section_evidence). Cans of about a box's size were taken for
  // it at 0.6 mm noise: 1.09-1.18 standing alone, 1.43 among clutter (pan-tilt tuning seed 269);
  // on the true boxes and cans of the tuning scenes the ratio was at most 0.98.
  double max_section_ratio = 1.05;
  // And a tapered single part rests on the table as posed (object_stability.hpp): settling onto
  // it turns it by at most this much (its fit's tilt; a cone fitted onto a box's top face,
  // apex down, or lying with its axis level topples).
  double max_settle_rad = 0.15;
  int max_candidates = 20;            // candidates checked for coverage before giving up
  double neighbourhood_factor = 1.2;  // r = factor * max(a) for refinement and verification
  Selection selection = Selection::kRankedVote;
  // Compound models: only combinations whose links deviate less than this (A of eq. 5.5, and D
  // of eq. 5.6 relative to d_k, plus 5 mm) are voted on; none: not found (kNotLinked). Keeps
  // perfect fits of look-alike parts from outvoting a correctly linked object.
  double link_angle_tolerance_rad = 0.26;
  double link_distance_tolerance = 0.15;
  int instances = 1;  // K instances wanted, best first, no two sharing a part position
  bool early_stop = true;
  int confirmations = 3;  // early stop: hypotheses agreeing with the leader (single-part models)
  // ... or, for a single-part model, this many when the scan covers at least full_coverage of
  // what the sensor could have measured of the leader and saw past none of it: placed by its own
  // surface, it is not waited on (the fig. 5.18 cone 19 -> 12 hypotheses). A compound model's
  // parts, set aside once established, keep `confirmations` (at 2 a stripe mallet was lost). A
  // leader whose hidden side leaves it free to slide is still waited on: a box behind a wall fitted
  // 9 mm along it, covered to 0.88, was taken after two agreeing hypotheses where the third found
  // the box (stripe tuning seed 160).
  int confirmations_covered = 2;
  int batch = 4;          // hypotheses per parallel batch (fixed: results do not depend on threads)
  // ... for a compound model's parts, which run all their hypotheses: a leader judged after every
  // 6 rather than 4 leaves a third fewer judgements and batch ends that hold the other threads
  // up (the mallet ~0.84x the time), and sets a rejected place's seeds aside 2 hypotheses later.
  int compound_batch = 6;
  int threads = 0;        // 0: all cores
  bool remove_plane = true;
  PlaneRemovalOptions plane;
  std::optional<Eigen::Vector3d> viewpoint;  // sensor position, when known (speeds up 5.1.2)
  // How the scan was taken (stripe sweep, pan-tilt, one viewpoint), when known: the coverage and
  // free-space checks then judge a part only by the surface this sensor could have measured.
  SensorView sensor;
  std::uint64_t seed = 1;
};

enum class DetectReason {
  kFound,
  kEmptyCloud,      // no points (or none left after the plane removal)
  kInvalidModel,    // no parts, invalid part parameters or links to missing parts
  kInvalidOptions,  // non-positive counts or tolerances
  kNoHypothesis,    // no RANSAC sample had enough neighbours to fit
  kNotConfirmed,    // hypotheses were fitted, but none passed the checks (see rejections)
  kNotLinked,       // compound model: confirmed parts, but no combination matches the links
};

const char* to_string(DetectReason reason);

// The checks a candidate part must pass to be confirmed (ObjectDetectOptions).
enum class Check {
  kMeasure,        // M > max_measure
  kInterior,       // I > max_interior_ratio (I + S)
  kSurfacePoints,  // S < min_surface_points
  kCoverage,       // coverage < min_coverage (or min_coverage_unknown_sensor); a compound
                   // object's over all its parts, each part's < min_coverage_compound_part
  kSeenThrough,    // seen_through > max_seen_through
  kOpenEnd,        // open_end > max_open_end: no surface by one of its flat ends
  kOpenRim,        // size left open by the points, and open_rim > max_open_rim: a flat cap
                   // reaches past the face the scan shows
  kSize,           // |size the points want - 1| > max_size_deviation
  kResidual,       // the points' spread about the surface (mm) above the scan's noise allows
  kHidden,         // fewer measurable (or grazed, with points) samples than
                   // min_measurable_samples (value: the count), or less than
                   // min_measurable_share of the facing ones (value: the share)
  kBelowPlane,     // reaches through the removed plane by more than the table margin, or than
                   // its points' uncertainty allows (sink_floor_mm; mm)
  kFloating,       // rest_on_plane: its lowest point is higher above the plane than the rest
                   // tolerance (mm)
  kContinues,      // the scan carries on past its flat faces (share of its surface points)
  kSection,        // the other cross-section fits its points better (max_section_ratio; the
                   // value: its rms over the other's)
  kTopples,        // a tapered single part would not rest as posed: settling onto the table
                   // turns it by more than max_settle_rad (rad; object_stability.hpp)
  kLink,           // compound: after the joint refinement a link's A (rad), D (mm) or bearing
                   // (mm: the sibling's centre from where the bearings put it) is off
};

const char* to_string(Check check);

struct PartScores {
  double measure = 0.0;          // M, eq. 5.2
  std::size_t interior = 0;      // I, eq. 5.3
  std::size_t surface = 0;       // S, eq. 5.4
  int rank_sum = 0;              // sum of this part's ranks in the vote
  int facing = 0;                // surface samples facing the sensor (object_coverage)
  int measurable = 0;            // of them, the ones not hidden behind measured surface
  int grazed = 0;                // of them, seen too obliquely to judge, with scan points on them
  double coverage = 0.0;         // share of them with scan points
  double seen_through = 0.0;     // share of them the sensor saw past
  double open_end = 0.0;         // share of the side wall by a flat end with no scan points
  double open_rim = 0.0;         // share of a flat cap's rim with no scan points (by sector)
  double lowest_mm = 0.0;        // height of its lowest point above the removed plane
  double below_plane_mm = 0.0;   // how far the model reaches through it (0: not at all)
  double height_sigma_mm = 0.0;  // standard deviation of its lowest point's height (pose fit)
  bool size_determined = false;  // the points determine the part's size (size_evidence)
  double size_scale = 1.0;       // the scale of the model they want
  // The points leave the length of a part with flat ends open (its ends not both seen): its
  // size is not verified along its axis.
  bool length_open = false;
  double residual_mm = 0.0;      // robust spread of their distances from the surface
  double continuation = 0.0;     // share of them the scan carries on past (object_continuation)
};

// Why a candidate was not confirmed: the first check it failed, its value and the limit.
struct Rejection {
  std::size_t part = 0;  // index into ObjectModel::parts
  Check check = Check::kMeasure;
  double value = 0.0;
  double limit = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // where the candidate part was
};

struct DetectedPart {
  std::string name;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
  PartScores scores;
  Eigen::Vector3d center() const { return T_world_part.translation(); }
  Eigen::Vector3d z_axis() const { return T_world_part.linear().col(2); }
  Eigen::Quaterniond rotation() const { return Eigen::Quaterniond(T_world_part.linear()); }
};

struct DetectedInstance {
  std::vector<DetectedPart> parts;             // in model order
  int rank_sum = 0;                            // total of the vote (lower is better)
  std::vector<double> link_angle_error_rad;    // A per link, eq. 5.5
  std::vector<double> link_distance_error_mm;  // D per link, eq. 5.6
  // Per link, the larger of the two parts' bearing errors (PartLink::bearing_rad); 0 for a link
  // without bearings.
  std::vector<double> link_bearing_error_rad;
};

struct StageTimes {
  double plane_ms = 0.0;
  double search_index_ms = 0.0;
  double hypotheses_ms = 0.0;
  double vote_ms = 0.0;
  double total_ms = 0.0;
};

struct ObjectDetectResult {
  DetectReason reason = DetectReason::kEmptyCloud;
  std::vector<DetectedInstance> instances;  // best first; empty unless found()
  PlaneRemovalResult plane;                 // the dominant plane (removed() tells if it was)
  // Not found: the candidates checked and why each failed, best first (for a hypothesis that
  // never reached the coverage checks, the check of eq. 5.2-5.4 it failed).
  std::vector<Rejection> rejections;
  int hypotheses_evaluated = 0;  // over all parts
  StageTimes time;
  bool found() const { return reason == DetectReason::kFound && !instances.empty(); }
};

ObjectDetectResult detect_object(const ObjectModel& model, std::span<const Eigen::Vector3d> points,
                                 const ObjectDetectOptions& options = {});

}  // namespace rangefit
