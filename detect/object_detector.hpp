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
// covers the surface it shows the sensor and, given the viewpoint, does not claim surface where
// the sensor saw past it (free space, detect/range_image.hpp).

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "detect/object_model.hpp"
#include "detect/plane_removal.hpp"
#include "detect/sensor_view.hpp"

namespace rangefit {

// How the final pose is chosen from the hypotheses (thesis 5.2.2, table 5.5).
enum class Selection {
  kMeasure,     // smallest M only (methods A and B)
  kRankedVote,  // lowest rank sum over M, I and S (methods C and D, and ours)
};

struct ObjectDetectOptions {
  int hypotheses = 32;           // m, at most: single-part models stop early once confirmed
  int compound_hypotheses = 12;  // m per part of compound models (always all of them)
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
  // And the scan holds points on this share of the surface the part shows the sensor
  // (object_coverage.hpp); checked on the vote's best candidates, occlusion lowers it.
  double min_coverage = 0.6;
  // With a viewpoint: and at most this share of that surface lies where the sensor saw past it
  // (free space, RangeImage). Rejects a part posed on a fragment of a larger object.
  double max_seen_through = 0.05;
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
  int batch = 4;          // hypotheses per parallel batch (fixed: results do not depend on threads)
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
  kNotConfirmed,    // hypotheses were fitted, but none fits and covers well enough
  kNotLinked,       // compound model: confirmed parts, but no combination matches the links
};

const char* to_string(DetectReason reason);

struct PartScores {
  double measure = 0.0;       // M, eq. 5.2
  std::size_t interior = 0;   // I, eq. 5.3
  std::size_t surface = 0;    // S, eq. 5.4
  int rank_sum = 0;           // sum of this part's ranks in the vote
  double coverage = 0.0;      // share of the visible surface with scan points (object_coverage)
  double seen_through = 0.0;  // share of it the sensor saw past (needs the viewpoint)
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
  int hypotheses_evaluated = 0;             // over all parts
  StageTimes time;
  bool found() const { return reason == DetectReason::kFound && !instances.empty(); }
};

ObjectDetectResult detect_object(const ObjectModel& model, std::span<const Eigen::Vector3d> points,
                                 const ObjectDetectOptions& options = {});

}  // namespace rangefit
