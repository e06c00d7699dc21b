#include "detect/object/object_detector.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>
#include <vector>

#include "detect/common/kdtree.hpp"
#include "detect/common/occupancy_grid.hpp"
#include "detect/common/parallel_for.hpp"
#include "detect/object/object_continuation.hpp"
#include "detect/object/object_coverage.hpp"
#include "detect/object/object_hypotheses.hpp"
#include "detect/object/object_link_region.hpp"
#include "detect/object/object_stability.hpp"
#include "detect/object/object_vote.hpp"

namespace rangefit {
namespace {

using Clock = std::chrono::steady_clock;

// The early stop trusts a leader only when almost no points lie inside it: a part fitted into
// a larger object (a cone into a cylinder) is found again and again, with ~10% of its points
// inside, and would otherwise stop the search before the real one turns up. Stricter than
// max_interior_ratio, which has to allow for noise; a noisy leader only costs the early stop.
constexpr double kCleanInteriorRatio = 0.02;

// After the joint refinement a compound object's links hold to this angle and this share of
// the link distance (plus the noise): the true mallets of the tuning scenes to 0.004 rad and 1.5
// mm of 170, a drum taken for the head 29 mm off.
constexpr double kRefinedLinkAngleRad = 0.1;
constexpr double kRefinedLinkShare = 0.04;

// How far a link's D (and its bearings, as the sibling's centre's offset) may be off once the
// parts are refined (kRefinedLinkShare), in mm; also how far from the link's places the linked
// search looks for a part.
double refined_link_limit_mm(const PartLink& link, double noise_mm) {
  return kRefinedLinkShare * link.distance_mm + 3.0 * noise_mm + 1.0;
}

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

bool model_ok(const ObjectModel& model) {
  if (model.parts.empty()) return false;
  for (const ModelPart& p : model.parts) {
    if (!p.shape.valid()) return false;
  }
  for (const PartLink& l : model.links) {
    if (l.first >= model.parts.size() || l.second >= model.parts.size() || l.first == l.second ||
        !std::isfinite(l.angle_rad) || !std::isfinite(l.distance_mm) || !l.bearings_valid()) {
      return false;
    }
  }
  return true;
}

bool options_ok(const ObjectDetectOptions& o) {
  return o.hypotheses >= 1 && o.compound_hypotheses >= 1 && o.trials >= 1 && o.sample_points >= 6 &&
         o.iterations >= 1 && o.init_iterations >= 1 && o.refine_rounds >= 0 && o.gamma > 0.0 &&
         o.gamma < 1.0 && o.neighbourhood_factor > 0.0 && o.instances >= 1 && o.batch >= 1 &&
         o.compound_batch >= 1 && o.linked_places >= 0 && o.linked_hypotheses >= 0 &&
         o.max_settle_rad >= 0.0 && o.confirmations >= 1 && o.confirmations_covered >= 1 &&
         o.refine_trim >= 0.0 && o.max_measure > 0.0 && o.max_interior_ratio >= 0.0 &&
         o.min_coverage >= 0.0 && o.min_coverage_unknown_sensor >= 0.0 &&
         o.min_coverage_compound_part >= 0.0 && o.max_seen_through >= 0.0 &&
         o.compound_screen_slack >= 1.0 && o.max_seen_through_posed_off >= 0.0 &&
         o.max_open_end >= 0.0 && o.max_open_end_compound >= 0.0 && o.max_open_rim >= 0.0 &&
         o.min_measurable_share_covered >= 0.0 && o.full_coverage >= 0.0 &&
         o.max_size_deviation > 0.0 && o.size_deviation_sigmas >= 0.0 && o.max_candidates >= 1 &&
         o.min_measurable_samples >= 0 && o.min_measurable_share >= 0.0 &&
         o.max_continuation >= 0.0 && o.max_section_ratio >= 1.0 && o.plane_margin_mm >= 0.0 &&
         o.rest_noise_factor >= 0.0 && o.rest_size_share >= 0.0 && o.sink_floor_mm >= 0.0 &&
         o.sink_noise_factor >= 0.0 && o.sink_sigma_factor >= 0.0 && valid(o.sensor);
}

// The check of eq. 5.2-5.4 that a hypothesis fails (see ObjectDetectOptions::max_measure).
std::optional<Rejection> implausible(const PartHypothesis& h, const ObjectDetectOptions& o) {
  const double in = static_cast<double>(h.scores.interior);
  const double on = static_cast<double>(h.scores.surface);
  const Eigen::Vector3d c = h.T_world_part.translation();
  if (!(h.scores.measure <= o.max_measure)) {
    return Rejection{0, Check::kMeasure, h.scores.measure, o.max_measure, c};
  }
  if (h.scores.surface < o.min_surface_points) {
    return Rejection{0, Check::kSurfacePoints, on, static_cast<double>(o.min_surface_points), c};
  }
  if (in > o.max_interior_ratio * (in + on)) {
    return Rejection{0, Check::kInterior, in / (in + on), o.max_interior_ratio, c};
  }
  return std::nullopt;
}

bool plausible(const PartHypothesis& h, const ObjectDetectOptions& o) {
  return h.valid && !implausible(h, o);
}

// The scan covers (nearly) all the sensor could have measured of a part and saw past none of it
// (ObjectDetectOptions::full_coverage): its own surface places it.
bool fully_covered(double covered, double seen_through, const ObjectDetectOptions& o) {
  return covered >= o.full_coverage && seen_through == 0.0;
}

// Confirmation by the surface evidence (see ObjectDetectOptions::min_coverage): the samples over
// the surface and the part's place against the table, not its ends (open_ended). For a part of
// a compound object the measurable share is judged over the whole object (its siblings hide
// some of it: the head hides the end of the shaft).
std::optional<Rejection> unconfirmed(const SurfaceCoverage& c, const ObjectDetectOptions& o,
                                     bool sensor_known, bool judge_share, double noise_mm) {
  // A compound object's part is held to the whole object's coverage (detect_object) and alone
  // only to the lower of the floor for parts and the unknown sensor's share.
  const double min_cover =
      !judge_share ? std::min(o.min_coverage_compound_part,
                              sensor_known ? o.min_coverage : o.min_coverage_unknown_sensor)
      : sensor_known ? o.min_coverage
                     : o.min_coverage_unknown_sensor;
  // Enough of it seen to judge: the measurable samples, and the grazed ones with points on them.
  const int evidence = c.measurable + c.grazed;
  if (evidence < o.min_measurable_samples) {
    return Rejection{0, Check::kHidden, static_cast<double>(evidence),
                     static_cast<double>(o.min_measurable_samples), Eigen::Vector3d::Zero()};
  }
  const double share = c.facing > 0 ? static_cast<double>(evidence) / c.facing : 0.0;
  // Less of it measurable, more of that must be there: below min_measurable_share only a part
  // whose measurable surface is (nearly) all covered is judged on.
  const bool all_there =
      share >= o.min_measurable_share_covered && fully_covered(c.covered, c.seen_through, o);
  if (judge_share && share < o.min_measurable_share && !all_there) {
    return Rejection{0, Check::kHidden, share, o.min_measurable_share, Eigen::Vector3d::Zero()};
  }
  const double sink_limit = table_margin_mm(o, c.min_size_mm, noise_mm);
  if (c.below_plane_mm > sink_limit) {
    return Rejection{0, Check::kBelowPlane, c.below_plane_mm, sink_limit, Eigen::Vector3d::Zero()};
  }
  if (c.seen_through > o.max_seen_through) {
    return Rejection{0, Check::kSeenThrough, c.seen_through, o.max_seen_through,
                     Eigen::Vector3d::Zero()};
  }
  if (!(c.covered >= min_cover))
    return Rejection{0, Check::kCoverage, c.covered, min_cover, Eigen::Vector3d::Zero()};
  return std::nullopt;
}

// The open-end check (see ObjectDetectOptions::max_open_end), of single parts only: a compound
// object's parts end by their siblings (a mallet's shaft by its head), and on the tuning scenes
// the check cost two true mallets.
std::optional<Rejection> open_ended(const SurfaceCoverage& c, const ObjectDetectOptions& o) {
  if (c.open_end > o.max_open_end)
    return Rejection{0, Check::kOpenEnd, c.open_end, o.max_open_end, Eigen::Vector3d::Zero()};
  return std::nullopt;
}

// Cells of the occupancy grid: about twice the scan's point spacing (so a measured surface has
// no holes for a line of sight to slip through), from the nearest neighbours of a spread sample.
double occupancy_cell_mm(std::span<const Eigen::Vector3d> points, const KdTree& tree) {
  constexpr std::size_t kSample = 256;
  if (points.size() < 2) return 2.0;
  std::vector<std::uint32_t> sample;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / kSample);
  for (std::size_t i = 0; i < points.size(); i += stride) {
    sample.push_back(static_cast<std::uint32_t>(i));
  }
  const std::optional<double> spacing = median_neighbour_distance(points, tree, sample);
  if (!spacing) return 2.0;
  return std::clamp(2.0 * *spacing, 1.5, 6.0);
}

// Same physical pose: the centres agree to 5% of the smallest size.
bool same_place(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const Superquadric& sq) {
  return (a.translation() - b.translation()).norm() < 0.05 * sq.min_size();
}

// A confirmed part with flat ends whose length its points leave open (its ends not both seen):
// a look-alike a few per cent shorter or longer than the model, its differing end in shadow,
// passes every check there, while the part itself may stand elsewhere in the scan with both ends
// seen. Such a part neither ends the search nor is taken before a part whose size the points
// verify: lying look-alike cans 7 and 14 % off were taken for the cylinder (pan-tilt tuning seeds
// 166, 268). Balls have no length; tapered parts are not asked (their continuation is not
// either).
bool size_unverified(const Superquadric& part, const PartScores& scores) {
  return scores.length_open && part.eps1 <= kFlatExponent && !part.ball() && !part.has_taper();
}

// Single-part vote over the evaluated hypotheses: index of the lowest rank sum (or smallest M).
std::vector<int> part_rank_sums(const std::vector<PartHypothesis>& hyps, Selection selection) {
  std::vector<double> m, in, s;
  for (const PartHypothesis& h : hyps) {
    m.push_back(h.scores.measure);
    in.push_back(static_cast<double>(h.scores.interior));
    s.push_back(static_cast<double>(h.scores.surface));
  }
  const std::vector<int> rm = ranks(m), ri = ranks(in), rs = ranks(s, true);
  std::vector<int> sum(hyps.size());
  for (std::size_t i = 0; i < hyps.size(); ++i) {
    sum[i] = selection == Selection::kMeasure ? rm[i] : rm[i] + ri[i] + rs[i];
  }
  return sum;
}

// Runs hypotheses [begin, end) of one part on the worker threads; results by index.
void run_batch(const HypothesisContext& ctx, const Superquadric& part, std::size_t part_index,
               std::size_t begin, std::size_t end, int threads, std::vector<PartHypothesis>& out) {
  parallel_for(end - begin, threads, [&](std::size_t i) {
    const std::size_t h = begin + i;
    out[h] = generate_hypothesis(ctx, part, mix_seed(ctx.options->seed, part_index, h));
  });
}

// The rest_on_plane check for a part, or the lowest part of an object (see
// ObjectDetectOptions::rest_on_plane); noise_mm is the table's noise.
std::optional<Rejection> floating(double lowest_mm, double max_size_mm, bool plane_removed,
                                  double noise_mm, const ObjectDetectOptions& o) {
  if (!o.rest_on_plane || !plane_removed) return std::nullopt;
  const double limit = rest_tolerance_mm(o, max_size_mm, noise_mm);
  if (lowest_mm > limit) {
    return Rejection{0, Check::kFloating, lowest_mm, limit, Eigen::Vector3d::Zero()};
  }
  return std::nullopt;
}

// How far a part may sink into the table when its lowest point's height has standard deviation
// sigma_mm under its fit (ObjectDetectOptions::sink_floor_mm).
double sink_limit_mm(const ObjectDetectOptions& o, double noise_mm, double sigma_mm) {
  return o.sink_floor_mm + o.sink_noise_factor * noise_mm + o.sink_sigma_factor * sigma_mm;
}

// The fit-quality checks in mm (see ObjectDetectOptions::max_size_deviation and
// residual_noise_factor), and, with `judge_sink` (a single part), its flat caps' rims where its
// size is left open (max_open_rim) and the part's sink into the table judged by how
// well its points place it (sink_floor_mm); noise_mm is the scan's range noise (the removed
// plane's rms). A compound object's parts are held to the table margin only: a mallet's shaft
// touches the table at its far end, 120 mm from its centre, and a true shaft of the tuning
// scenes was fitted 3.3 mm into the table there against a standard deviation of 0.28 mm.
std::optional<Rejection> misfit(const HypothesisContext& ctx, const Eigen::Isometry3d& T,
                                const SizeEvidence& e, double noise_mm, const SurfaceCoverage& seen,
                                bool judge_sink, PartScores* scores = nullptr) {
  const ObjectDetectOptions& o = *ctx.options;
  // Unknown when the fit had too few points: then only the table margin of unconfirmed() holds.
  double sigma = INFINITY;
  if (ctx.table && !e.pose_covariance.isZero()) {
    sigma = height_sigma_mm(T, seen.deepest_part, ctx.table->normal, e.pose_covariance);
  }
  if (scores) {
    scores->size_determined = e.determined;
    scores->size_scale = e.scale;
    scores->length_open = !e.along.has_value();
    scores->residual_mm = e.residual_mm;
    scores->below_plane_mm = seen.below_plane_mm;
    scores->height_sigma_mm = sigma;
  }
  const double max_residual = o.residual_noise_factor * noise_mm + o.max_residual_floor_mm;
  if (e.residual_mm > max_residual) {
    return Rejection{0, Check::kResidual, e.residual_mm, max_residual, T.translation()};
  }
  // Shorter along its axis than the model is no evidence where one of its flat ends is hidden:
  // the points end where the scan stops seeing the part, and the size fit takes that for its
  // end. A true box lying behind a wall that hid its near end read 5.8 % short (sigma 0.4 %).
  bool determined = e.determined;
  double scale = e.scale, allowance = e.allowance;
  if (e.along && *e.along < 1.0 && (seen.end_hidden[0] || seen.end_hidden[1])) {
    determined = e.across.has_value(), scale = e.across.value_or(1.0);
    allowance = e.across_allowance;
  }
  const double max_deviation = o.max_size_deviation + allowance;
  if (determined && std::abs(scale - 1.0) > max_deviation) {
    return Rejection{0, Check::kSize, scale - 1.0, max_deviation, T.translation()};
  }
  // The extent of its flat caps: a narrower look-alike's missing strip of cap, wherever the fit
  // placed it, and where the fit left the size across the axis open, also one farther in.
  const double rim = e.across_open ? std::max(seen.open_rim, seen.open_rim_far) : seen.open_rim;
  if (judge_sink && rim > o.max_open_rim) {
    return Rejection{0, Check::kOpenRim, rim, o.max_open_rim, T.translation()};
  }
  const double sink_limit = sink_limit_mm(o, noise_mm, sigma);
  if (judge_sink && ctx.table && seen.below_plane_mm > sink_limit) {
    return Rejection{0, Check::kBelowPlane, seen.below_plane_mm, sink_limit, T.translation()};
  }
  return std::nullopt;
}

// How far the scan carries on past the part's faces (see ObjectDetectOptions::
// max_continuation): the band is the scan's noise (three sigma, at least 1 mm), and the table is
// the one margin of the other table checks.
Continuation continuation_of(const HypothesisContext& ctx, const Superquadric& part,
                             const Eigen::Isometry3d& T, std::span<const PlacedPart> others,
                             double noise_mm) {
  ContinuationOptions co;
  co.band_mm = std::max(1.0, 3.0 * noise_mm);
  co.table = ctx.table;
  co.table_margin_mm = table_margin_mm(*ctx.options, part.min_size(), noise_mm);
  std::vector<PlacedShape> explained;
  for (const PlacedPart& p : others) explained.push_back({p.shape, p.T_world_part});
  return surface_continuation(part, T, ctx.points, *ctx.tree, co, explained);
}

std::optional<Rejection> continues(const Continuation& c, const Eigen::Isometry3d& T,
                                   const ObjectDetectOptions& o, PartScores* scores) {
  if (scores) scores->continuation = c.share;
  if (c.share > o.max_continuation) {
    return Rejection{0, Check::kContinues, c.share, o.max_continuation, T.translation()};
  }
  return std::nullopt;
}

// The open-end check of a compound object's part (ObjectDetectOptions::max_open_end_compound),
// once its siblings are placed: an end that faces a sibling (a shaft's end at its head) may end
// short of the scan's points there, the others may not. A head slid along its axis onto a rod
// that happens to lie at the link's distance that way leaves one end with its side wall shown
// farther in and none by the cap.
std::optional<Rejection> open_end_of_compound_part(const SurfaceCoverage& c,
                                                   const Eigen::Isometry3d& T,
                                                   std::span<const PlacedPart> others,
                                                   const ObjectDetectOptions& o) {
  constexpr double kFacesEnd = 0.5;  // cos of the cone around the axis in which a sibling faces
  const Eigen::Vector3d z = T.linear().col(2);
  double open = 0.0;
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 1 ? 1.0 : -1.0;
    const bool faces_sibling = std::any_of(others.begin(), others.end(), [&](const PlacedPart& p) {
      const Eigen::Vector3d v = p.T_world_part.translation() - T.translation();
      return sign * v.dot(z) > kFacesEnd * v.norm();
    });
    if (!faces_sibling) open = std::max(open, c.open_end_at[side]);
  }
  if (open > o.max_open_end_compound) {
    return Rejection{0, Check::kOpenEnd, open, o.max_open_end_compound, T.translation()};
  }
  return std::nullopt;
}

// A part the stability check asks (object_stability.hpp): visibly tapered, not a box or can
// whose learnt model has a taper of a few thousandths.
bool tapered(const Superquadric& part) {
  constexpr double kMinTaper = 0.2;
  return std::max(std::abs(part.kx), std::abs(part.ky)) >= kMinTaper;
}

// A part that the other cross-section fits better (ObjectDetectOptions::max_section_ratio).
std::optional<Rejection> other_section_fits(const HypothesisContext& ctx, const Superquadric& part,
                                            const Eigen::Isometry3d& T,
                                            const ObjectDetectOptions& o) {
  const SectionEvidence e = section_evidence(ctx, part, T);
  if (!e.asked || !(e.other_rms_mm > 0.0)) return std::nullopt;
  const double ratio = e.model_rms_mm / e.other_rms_mm;
  if (ratio <= o.max_section_ratio) return std::nullopt;
  return Rejection{0, Check::kSection, ratio, o.max_section_ratio, T.translation()};
}

// Every check a posed part must pass beyond eq. 5.2-5.4, at one pose (judge_part). `alone`: a
// part of a single-part model, whose measurable share and rest on the table are judged here; a
// part of a compound object is judged on those together with its siblings (detect_object). The
// coverage and fit scores go into `scores` and the coverage into `seen` when given.
std::optional<Rejection> judge_at(const HypothesisContext& ctx, const Superquadric& part,
                                  const Eigen::Isometry3d& T, std::span<const PlacedPart> others,
                                  const CoverageOptions& cover, double noise_mm, bool alone,
                                  PartScores* scores, SurfaceCoverage* seen) {
  const ObjectDetectOptions& o = *ctx.options;
  const bool known = cover.sensor.kind != SensorView::Kind::kUnknown;
  // The samples over the surface alone decide most rejections (hidden, sunk, seen through, not
  // covered) at a fraction of the cost of the rest: a box's rims are ~6 times as many samples.
  // Only a part that passes them has its ends and rims, size and continuation measured. Those do
  // not depend on one another: with more than one thread they are measured at once (a judge is
  // otherwise the one thing running between two batches of hypotheses; what a failed check leaves
  // unused was measured on a core that would have waited); on one thread each only when the
  // checks before it pass.
  SurfaceCoverage c = surface_coverage(part, T, ctx.points, *ctx.tree, cover, kSurfaceOnly);
  std::optional<Rejection> why = unconfirmed(c, o, known, alone, noise_mm);
  std::optional<SizeEvidence> size;
  std::optional<Continuation> continuation;
  if (!why) {
    SurfaceCoverage edges;
    if (thread_count(o.threads) > 1) {
      parallel_for(3, o.threads, [&](std::size_t k) {
        if (k == 0) edges = surface_coverage(part, T, ctx.points, *ctx.tree, cover, kEndsAndRims);
        if (k == 1) size = size_evidence(ctx, part, T, others);
        if (k == 2) continuation = continuation_of(ctx, part, T, others, noise_mm);
      });
    } else {
      edges = surface_coverage(part, T, ctx.points, *ctx.tree, cover, kEndsAndRims);
    }
    take_edges(c, edges);
  }
  if (seen) *seen = c;
  if (scores) {
    scores->facing = c.facing;
    scores->measurable = c.measurable;
    scores->grazed = c.grazed;
    scores->coverage = c.covered;
    scores->seen_through = c.seen_through;
    scores->open_end = c.open_end;
    scores->open_rim = c.open_rim;
    scores->lowest_mm = c.lowest_mm;
  }
  if (!why && alone) why = open_ended(c, o);
  if (!why && alone) {
    why = floating(c.lowest_mm, part.max_size(), cover.removed_plane.has_value(), noise_mm, o);
  }
  if (!why && alone && ctx.table && tapered(part)) {
    const double turn =
        settle_angle_rad(part, T.linear(), ctx.table->normal, 2.0 * o.max_settle_rad);
    if (turn > o.max_settle_rad) {
      why = Rejection{0, Check::kTopples, turn, o.max_settle_rad, T.translation()};
    }
  }
  if (!why && !alone && !others.empty()) why = open_end_of_compound_part(c, T, others, o);
  if (!why) {
    if (!size) size = size_evidence(ctx, part, T, others);
    why = misfit(ctx, T, *size, noise_mm, c, alone, scores);
  }
  if (!why) {
    if (!continuation) continuation = continuation_of(ctx, part, T, others, noise_mm);
    why = continues(*continuation, T, o, scores);
  }
  // Last: two more size fits, for a part that passed everything else.
  if (!why && alone) why = other_section_fits(ctx, part, T, o);
  if (why) why->centre = T.translation();
  return why;
}

// A check that the pose itself may fail: the refinement minimises G - 1, which weighs a box's
// narrow faces and rounded edges over the rest, and left the fig. 5.18 box at 45 deg 1-2 mm
// off, floating 3.24 mm against a limit of 3.20 or, in another local minimum, wanting 4.9 % more
// width. An open end too: a lying box turned ~10 deg about the table's normal (its start on the
// top face, the yaw left to a noisy, coarsely stepped flank) had the rings by one end off its
// side wall, 0.44 open against 0.3, and the polish turned it back. A ball is not asked again: its
// pose is its centre, which the refinement places well, and the polish turns it freely, and with it
// the axis of its free-size fit's two scales (a look-alike 5 % taller read 0.98 turned). Only a
// near miss is asked again (within kNearMiss x the limit): a polish moves a part by a millimetre or
// two, and a candidate sunk 30 mm into the table is another object.
bool pose_may_fail(const Rejection& why, const Superquadric& part) {
  constexpr double kNearMiss = 2.0;
  const bool pose_dependent = why.check == Check::kFloating || why.check == Check::kResidual ||
                              why.check == Check::kBelowPlane || why.check == Check::kSize ||
                              why.check == Check::kOpenEnd || why.check == Check::kTopples;
  return pose_dependent && !part.ball() && std::abs(why.value) <= kNearMiss * why.limit;
}

// A candidate that fails a check of how well it is posed by at most a fifth of the limit: the
// part may be there, posed a little off (a lying box started on its top face, its yaw still to
// find). Its points stay RANSAC seeds, so that later hypotheses may pose it better.
bool near_miss(const Rejection& why) {
  constexpr double kNearMissShare = 0.2;
  const bool posing = why.check == Check::kMeasure || why.check == Check::kSize ||
                      why.check == Check::kResidual || why.check == Check::kFloating ||
                      why.check == Check::kBelowPlane || why.check == Check::kOpenEnd ||
                      why.check == Check::kOpenRim || why.check == Check::kContinues ||
                      why.check == Check::kTopples;
  return posing && std::abs(why.value) <= (1.0 + kNearMissShare) * why.limit;
}

// judge_at at the given pose, and where a single part fails a check that depends on how well it
// is posed, once more at its pose fitted to the points' distances (object_hypotheses.hpp
// polish_pose). `T` becomes the pose that passed.
std::optional<Rejection> judge_part(const HypothesisContext& ctx, const Superquadric& part,
                                    Eigen::Isometry3d& T, std::span<const PlacedPart> others,
                                    const CoverageOptions& cover, double noise_mm, bool alone,
                                    PartScores* scores = nullptr, SurfaceCoverage* seen = nullptr) {
  std::optional<Rejection> why =
      judge_at(ctx, part, T, others, cover, noise_mm, alone, scores, seen);
  if (!why || !alone || !pose_may_fail(*why, part)) return why;
  const Eigen::Isometry3d polished = polish_pose(ctx, part, T, others);
  PartScores polished_scores;
  SurfaceCoverage polished_seen;
  if (judge_at(ctx, part, polished, others, cover, noise_mm, alone, &polished_scores,
               &polished_seen)) {
    return why;
  }
  T = polished;
  if (scores) {
    // The verdict measured the coverage there; the fit scores (M, I, S) are that pose's own
    // too, and the vote's rank stays.
    const PartScores fit = verify_pose(ctx, part, polished);
    polished_scores.measure = fit.measure;
    polished_scores.interior = fit.interior;
    polished_scores.surface = fit.surface;
    polished_scores.rank_sum = scores->rank_sum;
    *scores = polished_scores;
  }
  if (seen) *seen = polished_seen;
  return std::nullopt;
}

// Hypotheses of one part. After each batch the vote leader among the places not yet set aside
// is judged; a leader that fails a check is set aside, and so is one that passes and has been
// found again by `confirmations` hypotheses, for a compound model (its hypotheses stay in the
// vote, but a look-alike of the part is not fitted again and again while the real part waits;
// and for a single-part model asked for K instances, each of the first K - 1 established).
// A set-aside place's points are no longer drawn as RANSAC seeds, unless it failed by a near
// miss (near_miss). A single-part model stops once K leaders have passed and been found again by
// `confirmations` hypotheses each (`confirmations_covered` for a leader the scan covers fully).
// Batches are fixed, so the stop and the set-aside points are deterministic.
// A place judged during the search: its pose, scores and verdict, so that the final candidates
// do not judge it again.
struct Judged {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  PartScores scores;
  std::optional<Rejection> why;
  Eigen::Isometry3d passed_at = Eigen::Isometry3d::Identity();  // T, or its polish (judge_part)
};

// slide_pose along the part's own z-axis only (a box slid along x or y would leave the table).
Eigen::Isometry3d slide_along_axis(const HypothesisContext& ctx, const Superquadric& part,
                                   const WallRuns& wall, const Eigen::Vector3d& prefer) {
  const Eigen::Isometry3d& T = wall.T_world_part;
  const Eigen::Isometry3d to = slide_pose(ctx, part, wall, prefer);
  const Eigen::Vector3d z = T.linear().col(2);
  Eigen::Isometry3d along = T;
  along.translation() += z * z.dot(to.translation() - T.translation());
  return along;
}

// A single part slid towards `prefer` from the pose its wall's points were gathered at: along its
// axis only when asked that way (an end is open: the part rests on its other faces); a box asked
// across its flanks slides across them as well.
Eigen::Isometry3d slide_single(const HypothesisContext& ctx, const Superquadric& part,
                               const WallRuns& wall, const Eigen::Vector3d& prefer) {
  return prefer.z() == 0.0 ? slide_pose(ctx, part, wall, prefer)
                           : slide_along_axis(ctx, part, wall, prefer);
}

// A single part's candidate rejected because the scan carries on past one of its flat faces may
// be the part itself, fitted short of its wall's end: the fit leaves a lying box or can free to
// slide along its side walls (object_axial_slide.hpp), and a start on one end's patch stays
// there. Slid to where its wall's points end and refined again (nullopt: it does not move), it
// is judged as a candidate of its own (select_instances). A longer look-alike's wall is not slid
// along. The same for one rejected because the scan shows no side wall by one of its ends: the
// fit placed it past where its wall ends on that side (its other end hidden), and `prefer` slides
// it back as far as the wall's run allows. `slid`: the candidate T slid towards `prefer`
// (slide_single), already known to have moved.
std::optional<PartHypothesis> refined_slide(const HypothesisContext& ctx, const Superquadric& part,
                                            const Eigen::Isometry3d& T,
                                            const Eigen::Isometry3d& slid,
                                            const Eigen::Vector3d& prefer) {
  PartHypothesis h;
  h.valid = true;
  // The refinement leaves the part free along its wall, and may take it back: slid once more.
  h.T_world_part = refine_pose(ctx, part, slid);
  if (!prefer.isZero()) {
    h.T_world_part = slide_single(ctx, part, wall_at(ctx, part, h.T_world_part), prefer);
  }
  if (same_place(h.T_world_part, T, part)) return std::nullopt;
  h.scores = verify_pose(ctx, part, h.T_world_part);
  return h;
}

std::vector<PartHypothesis> search_part(const HypothesisContext& base, const Superquadric& part,
                                        std::size_t part_index, bool compound,
                                        const CoverageOptions& cover, double noise_mm,
                                        std::vector<Judged>& judged) {
  const ObjectDetectOptions& o = *base.options;
  const std::size_t m = static_cast<std::size_t>(compound ? o.compound_hypotheses : o.hypotheses);
  std::vector<PartHypothesis> all(m);
  std::vector<PlacedPart> set_aside, seeds_aside;
  std::size_t established = 0;
  HypothesisContext ctx = base;
  std::size_t done = 0;
  while (done < m) {
    const std::size_t end =
        std::min(m, done + static_cast<std::size_t>(compound ? o.compound_batch : o.batch));
    ctx.seed_excluded = seeds_aside;
    run_batch(ctx, part, part_index, done, end, o.threads, all);
    done = end;
    if (!o.early_stop || done >= m) continue;
    std::vector<PartHypothesis> valid;
    for (std::size_t i = 0; i < done; ++i) {
      const bool aside = std::any_of(set_aside.begin(), set_aside.end(), [&](const PlacedPart& r) {
        return same_place(all[i].T_world_part, r.T_world_part, part);
      });
      if (plausible(all[i], o) && !aside) valid.push_back(all[i]);
    }
    if (valid.empty()) continue;
    const std::vector<int> sums = part_rank_sums(valid, o.selection);
    const std::size_t lead =
        static_cast<std::size_t>(std::min_element(sums.begin(), sums.end()) - sums.begin());
    const Eigen::Isometry3d& T = valid[lead].T_world_part;
    // A leader that passed at an earlier batch's end and still leads is the same hypothesis,
    // waiting to be found again: its verdict stands (a rejected one was set aside).
    const std::size_t before = static_cast<std::size_t>(
        std::find_if(judged.begin(), judged.end(),
                     [&](const Judged& j) { return !j.why && j.T.matrix() == T.matrix(); }) -
        judged.begin());
    if (before == judged.size()) {
      Judged j{T, valid[lead].scores, std::nullopt, T};
      j.why = judge_part(ctx, part, j.passed_at, {}, cover, noise_mm, !compound, &j.scores);
      judged.push_back(std::move(j));
    }
    const Judged& verdict = judged[before];
    if (verdict.why) {
      set_aside.push_back({part, T});
      if (!near_miss(*verdict.why)) seeds_aside.push_back({part, T});
      continue;
    }
    int agree = 0;
    for (const PartHypothesis& h : valid) {
      if (same_place(h.T_world_part, T, part)) ++agree;
    }
    const PartScores& ls = valid[lead].scores;
    const bool clean = static_cast<double>(ls.interior) <=
                       kCleanInteriorRatio * static_cast<double>(ls.interior + ls.surface);
    const bool covered =
        !compound && fully_covered(verdict.scores.coverage, verdict.scores.seen_through, o);
    const int needed =
        covered ? std::min(o.confirmations, o.confirmations_covered) : o.confirmations;
    // A leader whose length the points leave open does not end the search (size_unverified).
    if (agree < needed || !clean || (!compound && size_unverified(part, verdict.scores))) {
      continue;
    }
    // One more place established: a single-part model stops once it has its K instances.
    if (!compound && ++established >= static_cast<std::size_t>(o.instances)) break;
    set_aside.push_back({part, T});
    seeds_aside.push_back({part, T});
  }
  all.resize(done);
  return all;
}

// Compound models: a part hypothesis is only combined with others when the scan shows the
// surface it claims (the coverage checks of judge_part, which do not depend on its siblings): a
// head posed in an overhanging plate or on a wall, seen through by the laser, otherwise fills
// the vote's best combinations and uses up the candidates before the real head is reached.
// Judged once per place; the failures' rejections (best hypothesis first, one per place) go to
// `why`.
std::vector<PartHypothesis> seen_as_claimed(const HypothesisContext& ctx, const Superquadric& part,
                                            std::size_t part_index,
                                            std::vector<PartHypothesis> hyps,
                                            const CoverageOptions& cover, double noise_mm,
                                            std::vector<Rejection>& why) {
  const ObjectDetectOptions& o = *ctx.options;
  const std::vector<int> sums = part_rank_sums(hyps, o.selection);
  std::vector<std::size_t> order(hyps.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return sums[a] < sums[b]; });
  // The places in rank order (a hypothesis at an earlier one's place shares its verdict), then
  // their coverage on all threads.
  std::vector<std::size_t> place_of(hyps.size()), first_of;
  for (std::size_t i : order) {
    const Eigen::Isometry3d& T = hyps[i].T_world_part;
    const auto it = std::find_if(first_of.begin(), first_of.end(), [&](std::size_t f) {
      return same_place(hyps[f].T_world_part, T, part);
    });
    place_of[i] = static_cast<std::size_t>(it - first_of.begin());
    if (it == first_of.end()) first_of.push_back(i);
  }
  ObjectDetectOptions screen = o;  // the hypothesis's own pose: see compound_screen_slack
  screen.max_seen_through *= o.compound_screen_slack;
  std::vector<std::optional<Rejection>> verdict(first_of.size());
  parallel_for(first_of.size(), o.threads, [&](std::size_t k) {
    const Eigen::Isometry3d& T = hyps[first_of[k]].T_world_part;
    const SurfaceCoverage c = surface_coverage(part, T, ctx.points, *ctx.tree, cover, kSurfaceOnly);
    verdict[k] =
        unconfirmed(c, screen, cover.sensor.kind != SensorView::Kind::kUnknown, false, noise_mm);
    if (verdict[k]) {
      verdict[k]->part = part_index;
      verdict[k]->centre = T.translation();
    }
  });
  for (const std::optional<Rejection>& r : verdict) {
    if (r) why.push_back(*r);
  }
  std::vector<PartHypothesis> out;
  for (std::size_t i = 0; i < hyps.size(); ++i) {
    if (!verdict[place_of[i]]) out.push_back(std::move(hyps[i]));
  }
  return out;
}

double folded(double angle) {
  const double a = std::fmod(std::abs(angle), std::numbers::pi);
  return std::min(a, std::numbers::pi - a);
}

// A, D and the bearing error of one link for two posed parts (eq. 5.5-5.6, PartLink).
struct LinkErrors {
  double angle_rad = 0.0, distance_mm = 0.0, bearing_rad = 0.0;
};

LinkErrors link_errors(const PartLink& l, const Eigen::Isometry3d& ti,
                       const Eigen::Isometry3d& tj) {
  const PartLink m = measure_link(l.first, l.second, ti, tj);
  LinkErrors e;
  e.angle_rad = std::abs(folded(l.angle_rad) - m.angle_rad);
  e.distance_mm = std::abs(l.distance_mm - m.distance_mm);
  if (l.bearing_rad && m.bearing_rad) {
    e.bearing_rad = std::max(std::abs((*l.bearing_rad)[0] - (*m.bearing_rad)[0]),
                             std::abs((*l.bearing_rad)[1] - (*m.bearing_rad)[1]));
  }
  return e;
}

// The vote's link gate (ObjectDetectOptions::link_angle_tolerance_rad, link_distance_tolerance).
bool within_gate(const ObjectDetectOptions& o, const PartLink& l, const LinkErrors& e) {
  return e.angle_rad <= o.link_angle_tolerance_rad && e.bearing_rad <= o.link_angle_tolerance_rad &&
         e.distance_mm <= o.link_distance_tolerance * l.distance_mm + 5.0;
}

// The shift along a part's own z-axis that the link asks for, given its sibling's centre `q`.
// With bearings, the one that puts `q` at the axial height the bearing gives (d cos bearing
// either way along the axis, the nearer): a mallet's head centred on its shaft's line, a shaft
// pointing at its head ended at the link's distance. Without, only when the axis points at the
// sibling: the shift that puts the centre at the link's distance (0 otherwise, and when no
// shift reaches it). Where the part's wall leaves its place along the axis open (its ends
// hidden), this is the evidence that remains.
Eigen::Vector3d link_prefer(const Eigen::Isometry3d& T, const Eigen::Vector3d& q,
                            const PartLink& link, bool first) {
  constexpr double kPointsAt = 0.8;  // |cos| of the angle between the axis and the link
  const double d = link.distance_mm;
  const Eigen::Vector3d z = T.linear().col(2), v = T.translation() - q;
  const double vz = v.dot(z);
  if (link.bearing_rad) {
    const double h = d * std::cos((*link.bearing_rad)[first ? 0 : 1]);
    const double s1 = -vz - h, s2 = -vz + h;
    return Eigen::Vector3d(0.0, 0.0, std::abs(s1) < std::abs(s2) ? s1 : s2);
  }
  const double disc = vz * vz - v.squaredNorm() + d * d;
  if (std::abs(vz) < kPointsAt * v.norm() || disc < 0.0) return Eigen::Vector3d::Zero();
  const double r = std::sqrt(disc), s1 = -vz + r, s2 = -vz - r;
  return Eigen::Vector3d(0.0, 0.0, std::abs(s1) < std::abs(s2) ? s1 : s2);
}

struct Combination {
  std::vector<std::size_t> pick;  // per part, index into its valid hypotheses
  std::vector<double> a, d, b;    // per link, eq. 5.5 and 5.6, and the bearing error
  int rank_sum = 0;
};

// All combinations of one valid hypothesis per part (the compound vote of 5.1.3). The parts'
// criteria and the links' A and D are all ranked over the combinations.
std::vector<Combination> vote(const ObjectModel& model,
                              const std::vector<std::vector<PartHypothesis>>& hyps,
                              const ObjectDetectOptions& options) {
  const Selection selection = options.selection;
  std::vector<Combination> combos;
  std::vector<std::size_t> pick(hyps.size(), 0);
  for (const auto& h : hyps) {
    if (h.empty()) return combos;
  }
  while (true) {
    Combination c;
    c.pick = pick;
    for (const PartLink& l : model.links) {
      const Eigen::Isometry3d& ti = hyps[l.first][pick[l.first]].T_world_part;
      const Eigen::Isometry3d& tj = hyps[l.second][pick[l.second]].T_world_part;
      const LinkErrors e = link_errors(l, ti, tj);
      c.a.push_back(e.angle_rad);
      c.d.push_back(e.distance_mm);
      c.b.push_back(e.bearing_rad);
    }
    combos.push_back(std::move(c));
    std::size_t p = 0;
    while (p < pick.size() && ++pick[p] == hyps[p].size()) pick[p++] = 0;
    if (p == pick.size()) break;
  }
  // Link gate: vote among the consistently linked combinations when there are any.
  std::vector<Combination> linked;
  for (const Combination& c : combos) {
    bool ok = true;
    for (std::size_t l = 0; l < model.links.size(); ++l) {
      ok = ok && within_gate(options, model.links[l], {c.a[l], c.d[l], c.b[l]});
    }
    if (ok) linked.push_back(c);
  }
  combos = std::move(linked);
  const auto add_ranks = [&](const std::vector<double>& v, bool larger_better) {
    const std::vector<int> r = ranks(v, larger_better);
    for (std::size_t i = 0; i < combos.size(); ++i) combos[i].rank_sum += r[i];
  };
  for (std::size_t p = 0; p < hyps.size(); ++p) {
    std::vector<double> m, in, s;
    for (const Combination& c : combos) {
      const PartScores& sc = hyps[p][c.pick[p]].scores;
      m.push_back(sc.measure);
      in.push_back(static_cast<double>(sc.interior));
      s.push_back(static_cast<double>(sc.surface));
    }
    add_ranks(m, false);
    if (selection == Selection::kRankedVote) {
      add_ranks(in, false);
      add_ranks(s, true);
    }
  }
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    std::vector<double> a, d, b;
    for (const Combination& c : combos) {
      a.push_back(c.a[l]), d.push_back(c.d[l]), b.push_back(c.b[l]);
    }
    add_ranks(a, false);
    add_ranks(d, false);
    if (model.links[l].bearing_rad) add_ranks(b, false);
  }
  std::stable_sort(combos.begin(), combos.end(), [](const Combination& x, const Combination& y) {
    return x.rank_sum < y.rank_sum;
  });
  return combos;
}

// Keeps at most `per_part` hypotheses of each part (best own rank sum first) so that the
// combinations of a compound model stay bounded.
std::vector<PartHypothesis> best_of(std::vector<PartHypothesis> valid, Selection selection,
                                    std::size_t per_part) {
  if (valid.size() <= per_part) return valid;
  const std::vector<int> sums = part_rank_sums(valid, selection);
  std::vector<std::size_t> order(valid.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return sums[a] < sums[b]; });
  std::vector<PartHypothesis> out;
  for (std::size_t i = 0; i < per_part; ++i) out.push_back(valid[order[i]]);
  return out;
}

// Compound models: each part of the chosen combination is refined once more with the points its
// sibling parts explain left out, best-fitting part first. Each part's hypotheses were refined
// alone, so points of the head leak into the shaft's trimmed least squares and pull its centre
// along its axis (the thesis's "false negative along the axis"); explained away, they cannot.
void refine_jointly(const HypothesisContext& ctx, const ObjectModel& model,
                    const CoverageOptions& cover, DetectedInstance& inst) {
  const std::size_t n = model.parts.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return inst.parts[a].scores.measure < inst.parts[b].scores.measure;
  });
  const auto siblings = [&](std::size_t p) {
    std::vector<PlacedPart> out;
    for (std::size_t q = 0; q < n; ++q) {
      if (q != p) out.push_back({model.parts[q].shape, inst.parts[q].T_world_part});
    }
    return out;
  };
  for (std::size_t p : order) {
    inst.parts[p].T_world_part =
        refine_pose(ctx, model.parts[p].shape, inst.parts[p].T_world_part, siblings(p));
  }
  // Each part with flat ends slid along its axes to where its wall's points end: a mallet's
  // head lies with its caps along the sweep (no points on them) and came out 4 mm short of its
  // wall's end, the trimmed fit leaving out the wall points past its cap. Where the wall leaves
  // the part free along its axis (its ends hidden), the link to its sibling places it, unless
  // that leaves one of its ends open (object_coverage.hpp open_end: the wall shown farther in,
  // none by the cap): a rod cut by the sweep's end is not pulled 25 mm towards a drum.
  for (std::size_t p = 0; p < n; ++p) {
    const Superquadric& shape = model.parts[p].shape;
    Eigen::Isometry3d& T = inst.parts[p].T_world_part;
    Eigen::Vector3d prefer = Eigen::Vector3d::Zero();
    for (const PartLink& link : model.links) {
      if (!prefer.isZero() || (link.first != p && link.second != p)) continue;
      const std::size_t q = link.first == p ? link.second : link.first;
      prefer = link_prefer(T, inst.parts[q].T_world_part.translation(), link, link.first == p);
    }
    const std::vector<PlacedPart> others = siblings(p);
    const WallRuns wall = wall_at(ctx, shape, T, others);
    const Eigen::Isometry3d least = slide_pose(ctx, shape, wall, Eigen::Vector3d::Zero());
    const Eigen::Isometry3d linked = prefer.isZero() ? least : slide_pose(ctx, shape, wall, prefer);
    const auto open_at = [&](const Eigen::Isometry3d& at) {
      const SurfaceCoverage c =
          surface_coverage(shape, at, ctx.points, *ctx.tree, cover, kEndsOnly);
      return std::array<double, 2>{c.open_end_at[0], c.open_end_at[1]};
    };
    const auto open = [](const std::array<double, 2>& a) { return std::max(a[0], a[1]); };
    const double limit = ctx.options->max_open_end_compound;
    T = least;
    std::optional<std::array<double, 2>> open_ends;
    if (!linked.isApprox(least)) {
      const std::array<double, 2> linked_open = open_at(linked);
      if (open(linked_open) <= limit) T = linked, open_ends = linked_open;
    }
    if (!open_ends) open_ends = open_at(least);
    // Still open at one end: the wall's run is shorter than the part (its other end hidden), and
    // the least slide stopped where the run first fits; slid on towards the open end's wall as
    // far as the run allows, it ends where the scan shows the part's end.
    if (open(*open_ends) > limit && shape.eps1 <= kFlatExponent) {
      Eigen::Vector3d close = Eigen::Vector3d::Zero();
      close.z() = (*open_ends)[0] > (*open_ends)[1] ? shape.a3 : -shape.a3;
      const Eigen::Isometry3d closed = slide_pose(ctx, shape, T, close, others);
      if (!closed.isApprox(T) && open(open_at(closed)) <= limit) T = closed;
    }
  }
  for (std::size_t p = 0; p < n; ++p) {
    const int rank_sum = inst.parts[p].scores.rank_sum;
    inst.parts[p].scores =
        verify_pose(ctx, model.parts[p].shape, inst.parts[p].T_world_part, siblings(p));
    inst.parts[p].scores.rank_sum = rank_sum;
  }
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const PartLink& link = model.links[l];
    const LinkErrors e = link_errors(link, inst.parts[link.first].T_world_part,
                                     inst.parts[link.second].T_world_part);
    inst.link_angle_error_rad[l] = e.angle_rad;
    inst.link_distance_error_mm[l] = e.distance_mm;
    inst.link_bearing_error_rad[l] = e.bearing_rad;
  }
}

// The scan without non-finite points (they cannot be fitted: dropped rather than fail), and
// what is left of it after 5.1.1's dominant plane removal.
struct Scan {
  std::vector<Eigen::Vector3d> finite;  // the whole scan; empty when the plane is kept
  std::vector<Eigen::Vector3d> cloud;   // the points the search fits
  std::span<const Eigen::Vector3d> whole() const {
    return finite.empty() ? std::span<const Eigen::Vector3d>(cloud) : finite;
  }
};

Scan prepare_scan(std::span<const Eigen::Vector3d> points, const ObjectDetectOptions& options,
                  ObjectDetectResult& result) {
  Scan scan;
  scan.finite.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    if (p.allFinite()) scan.finite.push_back(p);
  }
  if (scan.finite.empty()) return scan;
  const Clock::time_point t0 = Clock::now();
  if (options.remove_plane) {
    PlaneRemovalOptions plane = options.plane;
    plane.threads = options.threads;
    result.plane = remove_dominant_plane(scan.finite, plane);
    scan.cloud.reserve(result.plane.remaining.size());
    for (std::uint32_t i : result.plane.remaining) scan.cloud.push_back(scan.finite[i]);
  } else {
    scan.cloud = std::move(scan.finite);
    scan.finite.clear();
  }
  result.time.plane_ms = ms_since(t0);
  return scan;
}

// What the coverage checks know: the sensor (or a viewpoint), the scan's occupancy and the
// removed plane, oriented towards the objects (they rest on it, the sensor looks from their side).
CoverageOptions coverage_options(const ObjectDetectOptions& options,
                                 const PlaneRemovalResult& plane,
                                 std::span<const Eigen::Vector3d> cloud,
                                 const OccupancyGrid& occupancy) {
  CoverageOptions cover;
  cover.sensor = options.sensor;
  if (cover.sensor.kind == SensorView::Kind::kUnknown && options.viewpoint) {
    cover.sensor.kind = SensorView::Kind::kPoint;
    cover.sensor.origin = *options.viewpoint;
  }
  cover.occupancy = &occupancy;
  if (plane.removed()) {
    pca::Plane up = plane.plane;
    up.normal = pca::normal_towards(up, pca::centroid(cloud));
    cover.removed_plane = up;
  }
  cover.plane_margin_mm = options.plane_margin_mm;
  return cover;
}

// 5.1.2: m hypotheses per part. The plausible ones go to the vote (a compound part's only when
// seen as claimed, the best 40); the valid rest stay to say why nothing passed.
struct Hypotheses {
  std::vector<std::vector<PartHypothesis>> plausible, unfit;
  std::vector<Judged> judged;  // single-part models: places the search judged
  std::vector<Rejection> prefiltered;
  int evaluated = 0;
  bool any_valid = false, all_confirmed = true;
};

// The distinct places among a part's hypotheses, best rank sum first, at most `n`.
std::vector<Eigen::Isometry3d> best_places(const std::vector<PartHypothesis>& hyps,
                                           const Superquadric& part, Selection selection,
                                           std::size_t n) {
  const std::vector<int> sums = part_rank_sums(hyps, selection);
  std::vector<std::size_t> order(hyps.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return sums[a] < sums[b]; });
  std::vector<Eigen::Isometry3d> places;
  for (const std::size_t i : order) {
    if (places.size() >= n) break;
    const Eigen::Isometry3d& T = hyps[i].T_world_part;
    if (std::none_of(places.begin(), places.end(),
                     [&](const Eigen::Isometry3d& P) { return same_place(P, T, part); })) {
      places.push_back(T);
    }
  }
  return places;
}

// Beyond 5.1.2: more hypotheses of each part of a compound model, seeded where a link puts it
// from one of its sibling's best places (object_link_region.hpp), at each such place that none of
// its hypotheses is linked to yet (the vote's gate). The places are those the search over the
// whole scan found: these are added only once every part's are drawn. Deterministic: the seeds
// continue the part's own after its compound_hypotheses.
void add_linked_hypotheses(const HypothesisContext& base, const ObjectModel& model,
                           const CoverageOptions& cover, double noise_mm, Hypotheses& out) {
  const ObjectDetectOptions& o = *base.options;
  const std::vector<std::vector<PartHypothesis>>& found = out.plausible;
  std::vector<std::vector<PartHypothesis>> extras(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Superquadric& part = model.parts[p].shape;
    std::vector<PartHypothesis>& extra = extras[p];
    std::size_t next = static_cast<std::size_t>(o.compound_hypotheses);
    for (const PartLink& link : model.links) {
      if (link.first != p && link.second != p) continue;
      const bool first = link.first == p;
      const std::size_t q = first ? link.second : link.first;
      const auto linked_to = [&](const Eigen::Isometry3d& Tq) {
        return std::any_of(found[p].begin(), found[p].end(), [&](const PartHypothesis& h) {
          return within_gate(o, link,
                             first ? link_errors(link, h.T_world_part, Tq)
                                   : link_errors(link, Tq, h.T_world_part));
        });
      };
      for (const Eigen::Isometry3d& Tq : best_places(found[q], model.parts[q].shape, o.selection,
                                                     static_cast<std::size_t>(o.linked_places))) {
        if (linked_to(Tq)) continue;
        const std::vector<std::uint32_t> pool = link_region(
            link, first, part, Tq, refined_link_limit_mm(link, noise_mm), base.points, *base.tree);
        if (pool.empty()) continue;
        HypothesisContext ctx = base;
        ctx.seed_pool = pool;
        std::vector<PartHypothesis> hyps(static_cast<std::size_t>(o.linked_hypotheses));
        parallel_for(hyps.size(), o.threads, [&](std::size_t i) {
          hyps[i] = generate_hypothesis(ctx, part, mix_seed(o.seed, p, next + i));
        });
        next += hyps.size();
        out.evaluated += static_cast<int>(hyps.size());
        for (PartHypothesis& h : hyps) {
          if (plausible(h, o)) {
            extra.push_back(std::move(h));
          } else if (h.valid) {
            out.unfit[p].push_back(std::move(h));
          }
        }
      }
    }
    if (!extra.empty()) {
      extra = seen_as_claimed(base, part, p, std::move(extra), cover, noise_mm, out.prefiltered);
    }
  }
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    std::move(extras[p].begin(), extras[p].end(), std::back_inserter(out.plausible[p]));
  }
  out.all_confirmed = std::none_of(out.plausible.begin(), out.plausible.end(),
                                   [](const auto& h) { return h.empty(); });
}

Hypotheses search_parts(const HypothesisContext& ctx, const ObjectModel& model,
                        const CoverageOptions& cover, double noise_mm) {
  const ObjectDetectOptions& options = *ctx.options;
  const bool single = model.parts.size() == 1;
  Hypotheses out;
  out.plausible.resize(model.parts.size());
  out.unfit.resize(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    std::vector<Judged> judged_here;
    std::vector<PartHypothesis> all =
        search_part(ctx, model.parts[p].shape, p, !single, cover, noise_mm, judged_here);
    if (single) out.judged = std::move(judged_here);
    out.evaluated += static_cast<int>(all.size());
    std::vector<PartHypothesis>& kept = out.plausible[p];
    for (PartHypothesis& h : all) {
      out.any_valid = out.any_valid || h.valid;
      if (plausible(h, options)) {
        kept.push_back(std::move(h));
      } else if (h.valid) {
        out.unfit[p].push_back(std::move(h));
      }
    }
    if (!single) {
      kept = seen_as_claimed(ctx, model.parts[p].shape, p, std::move(kept), cover, noise_mm,
                             out.prefiltered);
      kept = best_of(std::move(kept), options.selection, 40);
    }
    out.all_confirmed = out.all_confirmed && !kept.empty();
  }
  if (!single && options.linked_hypotheses > 0)
    add_linked_hypotheses(ctx, model, cover, noise_mm, out);
  return out;
}

// The instance a combination of the vote picks, its parts at the hypotheses' poses.
DetectedInstance instance_of(const ObjectModel& model, const Hypotheses& hyps,
                             const Combination& c) {
  DetectedInstance inst;
  inst.rank_sum = c.rank_sum;
  inst.link_angle_error_rad = c.a;
  inst.link_distance_error_mm = c.d;
  inst.link_bearing_error_rad = c.b;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const PartHypothesis& h = hyps.plausible[p][c.pick[p]];
    DetectedPart part;
    part.name = model.parts[p].name;
    part.T_world_part = h.T_world_part;
    part.scores = h.scores;
    part.scores.rank_sum = c.rank_sum;
    inst.parts.push_back(std::move(part));
  }
  return inst;
}

// The links once more after the joint refinement, tighter than the vote's gate: parts that only
// roughly fit the link (a head-sized drum 30 mm off the shaft's end) drift apart when each is
// refined on its own points, a mallet's parts stay within a few millimetres.
std::optional<Rejection> refined_links(const ObjectModel& model, const DetectedInstance& inst,
                                       double noise_mm) {
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const double limit = refined_link_limit_mm(model.links[l], noise_mm);
    const double a = inst.link_angle_error_rad[l], d = inst.link_distance_error_mm[l];
    const Eigen::Vector3d centre = inst.parts[model.links[l].first].center();
    if (a > kRefinedLinkAngleRad) {
      return Rejection{model.links[l].first, Check::kLink, a, kRefinedLinkAngleRad, centre};
    }
    if (d > limit) return Rejection{model.links[l].first, Check::kLink, d, limit, centre};
    // The bearings to the same limit, as the sibling centre's distance from where they put it.
    const double across = inst.link_bearing_error_rad[l] * model.links[l].distance_mm;
    if (across > limit) return Rejection{model.links[l].first, Check::kLink, across, limit, centre};
  }
  return std::nullopt;
}

// A compound object rests on the table with at least one part: a part may sink into it by
// more than its points allow (a mallet's shaft touches the table at its far end, 120 mm from its
// centre, and was fitted 3.3 mm into it against a standard deviation of 0.28 mm), but not all of
// them. A look-alike mallet 10 % smaller, fitted to the model, sank 6 mm with both parts, its
// head's lowest point placed to 0.16 mm (misfit: sink_floor_mm and the factors).
std::optional<Rejection> sunk_compound(const HypothesisContext& ctx, const DetectedInstance& inst,
                                       double noise_mm) {
  if (!ctx.table || inst.parts.size() < 2) return std::nullopt;
  const ObjectDetectOptions& o = *ctx.options;
  std::optional<Rejection> least;
  double least_excess = INFINITY;
  for (std::size_t p = 0; p < inst.parts.size(); ++p) {
    const PartScores& s = inst.parts[p].scores;
    const double limit = sink_limit_mm(o, noise_mm, s.height_sigma_mm);
    if (!(s.below_plane_mm > limit)) return std::nullopt;
    if (s.below_plane_mm - limit < least_excess) {
      least_excess = s.below_plane_mm - limit;
      least = Rejection{p, Check::kBelowPlane, s.below_plane_mm, limit, inst.parts[p].center()};
    }
  }
  return least;
}

// Eq. 5.2-5.4 and the coverage checks on every part of a candidate instance (its scores
// updated), then a compound object's measurable share, coverage and rest on the table over all
// its parts. `before`: a single part's place the search judged already, its verdict reused.
std::optional<Rejection> confirm(const HypothesisContext& ctx, const ObjectModel& model,
                                 const CoverageOptions& cover, double noise_mm,
                                 const Judged* before, DetectedInstance& inst) {
  const ObjectDetectOptions& options = *ctx.options;
  const bool single = model.parts.size() == 1;
  if (before) {
    if (before->why) return before->why;
    inst.parts[0].T_world_part = before->passed_at;
    const int rank_sum = inst.parts[0].scores.rank_sum;
    inst.parts[0].scores = before->scores;
    inst.parts[0].scores.rank_sum = rank_sum;
    return std::nullopt;
  }
  if (std::optional<Rejection> why = refined_links(model, inst, noise_mm)) return why;
  double lowest = INFINITY, lowest_size = 0.0;
  std::size_t lowest_part = 0;
  int facing = 0, measurable = 0, evidence = 0;  // evidence: with the grazed samples
  double covered = 0.0;  // measurable samples with scan points, over all parts
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    DetectedPart& part = inst.parts[p];
    std::vector<PlacedPart> others;
    for (std::size_t q = 0; q < model.parts.size(); ++q) {
      if (q != p) others.push_back({model.parts[q].shape, inst.parts[q].T_world_part});
    }
    SurfaceCoverage seen;
    std::optional<Rejection> why = judge_part(ctx, model.parts[p].shape, part.T_world_part,
                                              others, cover, noise_mm, single, &part.scores, &seen);
    if (why) {
      why->part = p;
      return why;
    }
    if (seen.lowest_mm < lowest) {
      lowest = seen.lowest_mm, lowest_size = model.parts[p].shape.max_size(), lowest_part = p;
    }
    facing += seen.facing, measurable += seen.measurable;
    evidence += seen.measurable + seen.grazed;
    covered += seen.covered * seen.measurable;
  }
  if (single) return std::nullopt;
  if (evidence < options.min_measurable_share * facing) {
    return Rejection{0, Check::kHidden, facing > 0 ? static_cast<double>(evidence) / facing : 0.0,
                     options.min_measurable_share, inst.parts[0].center()};
  }
  const double min_cover = cover.sensor.kind != SensorView::Kind::kUnknown
                               ? options.min_coverage
                               : options.min_coverage_unknown_sensor;
  if (measurable > 0 && covered < min_cover * measurable) {
    return Rejection{0, Check::kCoverage, covered / measurable, min_cover, inst.parts[0].center()};
  }
  std::optional<Rejection> why =
      floating(lowest, lowest_size, cover.removed_plane.has_value(), noise_mm, options);
  if (why) why->part = lowest_part, why->centre = inst.parts[lowest_part].center();
  if (!why) why = sunk_compound(ctx, inst, noise_mm);
  return why;
}

// The place a single part's search judged already, if the candidate is at it.
const Judged* judged_before(const ObjectModel& model, const Hypotheses& hyps,
                            const DetectedInstance& inst) {
  if (model.parts.size() != 1) return nullptr;
  const Eigen::Isometry3d& T = inst.parts[0].T_world_part;
  for (const Judged& j : hyps.judged) {
    if (j.why ? same_place(j.T, T, model.parts[0].shape) : j.T.matrix() == T.matrix()) return &j;
  }
  return nullptr;
}

// The checks a single part fails when it is posed off (along or across its wall, or turned about
// the table's normal) rather than absent: slide_to_confirm and turn_to_confirm answer them. Space
// seen through half of what the sensor should see of it is not a part posed off but a part where
// nothing is (max_seen_through_posed_off).
bool posed_off(const Rejection& why, const ObjectDetectOptions& o) {
  if (why.check == Check::kSeenThrough) return why.value < o.max_seen_through_posed_off;
  return why.check == Check::kContinues || why.check == Check::kOpenEnd ||
         why.check == Check::kOpenRim;
}

// `inst`, a single part, moved to pose T with the fit scores there (its vote's rank kept) when it
// is confirmed there: true, and `inst` is the moved one; false, and `inst` is as it was.
bool move_if_confirmed(const HypothesisContext& ctx, const ObjectModel& model,
                       const CoverageOptions& cover, double noise_mm, const Eigen::Isometry3d& T,
                       const PartScores& scores, DetectedInstance& inst) {
  DetectedInstance moved = inst;
  moved.parts[0].T_world_part = T;
  moved.parts[0].scores = scores;
  moved.parts[0].scores.rank_sum = inst.parts[0].scores.rank_sum;
  if (confirm(ctx, model, cover, noise_mm, nullptr, moved)) return false;
  inst = std::move(moved);
  return true;
}

// A single part rejected for carrying on past a flat face, for an open end, for a cap whose
// rim reaches past the face the scan shows or for space the sensor saw through (all four: posed
// off along its wall; a box beside an overhang's leg stood 14 mm along its axis, its end where
// the laser saw the table), slid along its wall (refined_slide) and confirmed there: `inst` is
// moved to the slid pose and true is returned.
bool slide_to_confirm(const HypothesisContext& ctx, const ObjectModel& model,
                      const CoverageOptions& cover, double noise_mm, const Rejection& failed,
                      DetectedInstance& inst) {
  if (model.parts.size() != 1 || !posed_off(failed, *ctx.options)) return false;
  const Superquadric& part = model.parts[0].shape;
  const Eigen::Isometry3d& T = inst.parts[0].T_world_part;
  // Where along the wall: as little as possible; from an open end, back towards the other; from
  // space seen through, a cap's rim reaching past the face the scan shows or a scan carrying on
  // past a face, which end is off is not known, so either way as well, as far as the wall's run
  // allows. Lying boxes whose one end was hidden were fitted 13 and 37 mm along their axis past
  // that end: their wall's run fit within them from there too, so "as little as possible" left
  // them in place, and the scan carried on past the other end (pan-tilt tuning seeds 29, 171).
  // A box is slid across its flanks too, either way: a standing box seen on part of its top (a
  // wall hid the rest) was fitted 15 mm across, where the laser saw the table past it (pan-tilt
  // tuning seed 86).
  std::vector<Eigen::Vector3d> prefer{Eigen::Vector3d::Zero()};
  if (failed.check == Check::kOpenEnd) {
    const SurfaceCoverage c = surface_coverage(part, T, ctx.points, *ctx.tree, cover, kEndsOnly);
    const double minus = std::max(c.open_end_at[0], c.open_end_far_at[0]);
    const double plus = std::max(c.open_end_at[1], c.open_end_far_at[1]);
    prefer[0].z() = plus > minus ? -part.a3 : part.a3;
  } else {
    prefer.push_back(Eigen::Vector3d(0.0, 0.0, part.a3));
    prefer.push_back(Eigen::Vector3d(0.0, 0.0, -part.a3));
    if (part.eps2 <= kFlatExponent) {
      for (double sign : {1.0, -1.0}) {
        prefer.push_back(Eigen::Vector3d(sign * part.a1, 0.0, 0.0));
        prefer.push_back(Eigen::Vector3d(0.0, sign * part.a2, 0.0));
      }
    }
  }
  // The wall's points gathered once; the ways that move the part at all refined as many at once
  // as there are threads, then judged in order: the first that is confirmed is taken, as when
  // each was slid in turn.
  const WallRuns wall = wall_at(ctx, part, T);
  std::vector<std::pair<Eigen::Isometry3d, Eigen::Vector3d>> moves;  // (slid pose, prefer)
  for (const Eigen::Vector3d& towards : prefer) {
    const Eigen::Isometry3d slid = slide_single(ctx, part, wall, towards);
    if (!same_place(slid, T, part)) moves.emplace_back(slid, towards);
  }
  const std::size_t batch = thread_count(ctx.options->threads);
  for (std::size_t first = 0; first < moves.size(); first += batch) {
    std::vector<std::optional<PartHypothesis>> slid(std::min(batch, moves.size() - first));
    parallel_for(slid.size(), ctx.options->threads, [&](std::size_t k) {
      slid[k] = refined_slide(ctx, part, T, moves[first + k].first, moves[first + k].second);
    });
    for (const std::optional<PartHypothesis>& h : slid) {
      if (h && move_if_confirmed(ctx, model, cover, noise_mm, h->T_world_part, h->scores, inst)) {
        return true;
      }
    }
  }
  return false;
}

// The turns about the table's normal (deg) worth trying for a part at pose T. Lying (its axis
// within 10 deg of the table's plane): an eighth and a quarter turn either way, the turns a start
// on a patch of its top gets wrong. Standing (within 10 deg of the normal): the turn is about its
// own axis, so only the turns its section does not repeat under, an eighth for a square section
// and none for a round one. Tilted between: none; on tuning 1..300 (box and cylinder, stripe and
// pan-tilt) none of 96 tilted candidates' turns was confirmed, nor 117 standing cylinders'.
std::span<const double> turns_to_try(const Superquadric& part, const Eigen::Isometry3d& T,
                                     const Eigen::Vector3d& normal) {
  static constexpr std::array<double, 3> kAll{45.0, -45.0, 90.0};
  const double tilt_sin = std::sin(10.0 * std::numbers::pi / 180.0);
  const double up = std::abs(T.linear().col(2).dot(normal));
  if (up < tilt_sin) return kAll;
  if (up < std::sqrt(1.0 - tilt_sin * tilt_sin)) return {};
  if (std::abs(part.a1 - part.a2) > 1e-6 * part.a1) return kAll;
  return part.eps2 > kFlatExponent ? std::span<const double>{} : std::span(kAll).first(1);
}

// A single part rejected as slide_to_confirm's are, turned about the table's normal by the turns
// that can change what the scan sees of it (turns_to_try), each turn fitted again (refine_pose);
// the best fit is kept when it fits the points better than the candidate did and is confirmed:
// `inst` is moved there and true is returned. A start on a patch of a top face turns the part
// about the table's normal by chance (the moments of a round patch of a plane), and the
// refinement settles in the nearest minimum: lying boxes seen from above were rejected turned by
// 11, 20 and 90 deg, M 0.11-0.17 against 0.02-0.07 where they lay (pan-tilt tuning seeds 225,
// 195, 197). A ball has no turn to find, and a tapered round part (a cone) is not turned either:
// none of 572 turns of the cone passed (tuning 1..300, stripe and pan-tilt), and they took a third
// of an absent cone's time. Lying cylinders are still turned: without it their tuning rates were
// the same, but one held-out pan-tilt cylinder (each part lost <= 40 %) was lost.
bool turn_to_confirm(const HypothesisContext& ctx, const ObjectModel& model,
                     const CoverageOptions& cover, double noise_mm, const Rejection& failed,
                     DetectedInstance& inst) {
  if (model.parts.size() != 1 || !posed_off(failed, *ctx.options) || !ctx.table) return false;
  const Superquadric& part = model.parts[0].shape;
  if (part.ball() || (part.has_taper() && part.eps2 > kFlatExponent)) return false;
  const Eigen::Isometry3d& T = inst.parts[0].T_world_part;
  const std::span<const double> turns_deg = turns_to_try(part, T, ctx.table->normal);
  std::vector<PartHypothesis> turned(turns_deg.size());  // each turn refined, on all threads
  parallel_for(turns_deg.size(), ctx.options->threads, [&](std::size_t k) {
    Eigen::Isometry3d at = T;
    at.linear() = Eigen::AngleAxisd(turns_deg[k] * std::numbers::pi / 180.0, ctx.table->normal)
                      .toRotationMatrix() *
                  T.linear();
    at = refine_pose(ctx, part, at);
    turned[k].T_world_part = at;
    turned[k].valid = !same_place(at, T, part);
    if (turned[k].valid) turned[k].scores = verify_pose(ctx, part, at);
  });
  std::optional<PartHypothesis> best;
  for (const PartHypothesis& h : turned) {
    if (!h.valid) continue;
    const double to_beat = best ? best->scores.measure : inst.parts[0].scores.measure;
    if (!(h.scores.measure < to_beat)) continue;
    best = h;
  }
  return best &&
         move_if_confirmed(ctx, model, cover, noise_mm, best->T_world_part, best->scores, inst);
}

// A confirmed single part with flat ends whose wall's points run past one end and stop short of
// the other (its far end hidden) is slid along its axis until they end with it, and kept there
// when it is confirmed there as well. The continuation check does not see a few millimetres past
// the part's rounded edge, and the fit leaves the part free along its wall.
void settle_along_wall(const HypothesisContext& ctx, const ObjectModel& model,
                       const CoverageOptions& cover, double noise_mm, DetectedInstance& inst) {
  if (model.parts.size() != 1) return;
  const Superquadric& part = model.parts[0].shape;
  const Eigen::Isometry3d& T = inst.parts[0].T_world_part;
  constexpr double kMinMoveMm = 0.5;
  const Eigen::Isometry3d along =
      slide_along_axis(ctx, part, wall_at(ctx, part, T), Eigen::Vector3d::Zero());
  if ((along.translation() - T.translation()).norm() < kMinMoveMm) return;
  move_if_confirmed(ctx, model, cover, noise_mm, along, verify_pose(ctx, part, along), inst);
}

// Selection: the ranked vote's combinations (5.1.2, extended by the links, 5.1.3) confirmed in
// rank order until K distinct instances stand. Candidates already checked are kept by their part
// centres: a rejected place is not checked again, and no part of a new instance may sit where a
// part of an accepted one does.
void select_instances(const HypothesisContext& ctx, const ObjectModel& model,
                      const CoverageOptions& cover, double noise_mm, const Hypotheses& hyps,
                      ObjectDetectResult& result) {
  const ObjectDetectOptions& options = *ctx.options;
  const std::vector<Combination> combos = vote(model, hyps.plausible, options);
  std::vector<std::vector<Eigen::Vector3d>> rejected, accepted;
  // Confirmed single parts whose size the points leave unverified (size_unverified), in rank
  // order: they fill the instances still wanted once every combination has been judged.
  std::vector<std::pair<std::vector<Eigen::Vector3d>, DetectedInstance>> unverified;
  const auto overlaps = [&](const std::vector<Eigen::Vector3d>& a,
                            const std::vector<Eigen::Vector3d>& b, bool any) {
    bool all_same = true, any_same = false;
    for (std::size_t p = 0; p < a.size(); ++p) {
      const double r = 0.5 * model.parts[p].shape.min_size();
      all_same = all_same && (a[p] - b[p]).norm() < r;
      for (const Eigen::Vector3d& q : b) any_same = any_same || (a[p] - q).norm() < r;
    }
    return any ? any_same : all_same;
  };
  for (const Combination& c : combos) {
    if (static_cast<int>(result.instances.size()) >= options.instances) break;
    std::vector<Eigen::Vector3d> centres;
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
      centres.push_back(hyps.plausible[p][c.pick[p]].T_world_part.translation());
    }
    const auto same = [&](const std::vector<Eigen::Vector3d>& x) {
      return overlaps(centres, x, false);
    };
    const auto clash = [&](const std::vector<Eigen::Vector3d>& x) {
      return overlaps(centres, x, true);
    };
    if (std::any_of(accepted.begin(), accepted.end(), clash) ||
        std::any_of(rejected.begin(), rejected.end(), same)) {
      continue;
    }
    if (static_cast<int>(rejected.size() + accepted.size()) >= options.max_candidates) break;
    DetectedInstance inst = instance_of(model, hyps, c);
    if (model.parts.size() > 1) refine_jointly(ctx, model, cover, inst);
    if (std::optional<Rejection> why =
            confirm(ctx, model, cover, noise_mm, judged_before(model, hyps, inst), inst)) {
      result.rejections.push_back(*why);
      rejected.push_back(std::move(centres));
      if (!slide_to_confirm(ctx, model, cover, noise_mm, *why, inst) &&
          !turn_to_confirm(ctx, model, cover, noise_mm, *why, inst)) {
        continue;
      }
      centres = {inst.parts[0].center()};
      if (std::any_of(accepted.begin(), accepted.end(), clash)) continue;
    } else {
      settle_along_wall(ctx, model, cover, noise_mm, inst);
    }
    if (model.parts.size() == 1 && size_unverified(model.parts[0].shape, inst.parts[0].scores)) {
      unverified.push_back({{inst.parts[0].center()}, std::move(inst)});
      continue;
    }
    for (std::size_t p = 0; p < model.parts.size(); ++p) centres.push_back(inst.parts[p].center());
    accepted.push_back(std::move(centres));
    result.instances.push_back(std::move(inst));
  }
  for (auto& held : unverified) {
    if (static_cast<int>(result.instances.size()) >= options.instances) break;
    const auto clash = [&](const std::vector<Eigen::Vector3d>& x) {
      return overlaps(held.first, x, true);
    };
    if (std::any_of(accepted.begin(), accepted.end(), clash)) continue;
    accepted.push_back(held.first);
    result.instances.push_back(std::move(held.second));
  }
}

// A confirmed instance that stands square on the table (each part's axes within ~10 deg of its
// normal or of its plane: on a face, a base or a flank; a ball in any pose) set down on it along
// its normal, its lowest point on it: parts rest on the table (ObjectDetectOptions::rest_on_plane),
// and the table's plane, fitted to far more points, places the height better than the fit to the
// part's own points, which noise leaves a millimetre or more high or low where the part's lower
// half is hidden. A tilted part may lean on something else (the fig. 5.18 box and cylinder): left
// as fitted. The checks judged the fitted pose; they allowed it this far off the table.
void set_on_table(const ObjectModel& model, const pca::Plane& table, DetectedInstance& inst) {
  std::optional<double> lowest;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Eigen::Isometry3d& T = inst.parts[p].T_world_part;
    if (!model.parts[p].shape.ball() && !stands_square(T, table)) return;
    const std::optional<double> above = lowest_above(model.parts[p].shape, T, table);
    if (above && (!lowest || *above < *lowest)) lowest = above;
  }
  if (!lowest) return;
  for (DetectedPart& part : inst.parts) part.T_world_part.translation() -= *lowest * table.normal;
}

// Why nothing was found, the failed checks named (thesis 5.1: a reason for every answer).
void explain_not_found(const ObjectModel& model, const ObjectDetectOptions& options,
                       Hypotheses& hyps, ObjectDetectResult& result) {
  const bool single = model.parts.size() == 1;
  if (!hyps.any_valid) {
    result.reason = DetectReason::kNoHypothesis;
    return;
  }
  if (hyps.all_confirmed && !single && result.rejections.empty()) {
    result.reason = DetectReason::kNotLinked;  // plausible parts, but no linked combination
    return;
  }
  result.reason = DetectReason::kNotConfirmed;
  if (result.rejections.empty()) result.rejections = std::move(hyps.prefiltered);
  if (!result.rejections.empty()) return;
  // No hypothesis passed eq. 5.2-5.4: say which check the best-fitting ones failed.
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    if (!hyps.plausible[p].empty()) continue;
    const PartHypothesis* best = nullptr;
    for (const PartHypothesis& h : hyps.unfit[p]) {
      if (!best || h.scores.measure < best->scores.measure) best = &h;
    }
    if (!best) continue;
    if (std::optional<Rejection> r = implausible(*best, options)) {
      r->part = p;
      result.rejections.push_back(*r);
    }
  }
}

}  // namespace

const char* to_string(Check check) {
  switch (check) {
    case Check::kMeasure:
      return "measure";
    case Check::kInterior:
      return "interior";
    case Check::kSurfacePoints:
      return "surface points";
    case Check::kCoverage:
      return "coverage";
    case Check::kSeenThrough:
      return "seen through";
    case Check::kOpenEnd:
      return "open end";
    case Check::kOpenRim:
      return "open rim";
    case Check::kSize:
      return "size";
    case Check::kResidual:
      return "residual";
    case Check::kHidden:
      return "hidden";
    case Check::kBelowPlane:
      return "below plane";
    case Check::kFloating:
      return "floating";
    case Check::kTopples:
      return "topples";
    case Check::kContinues:
      return "continues";
    case Check::kSection:
      return "section";
    case Check::kLink:
      return "link";
  }
  return "unknown";
}

const char* to_string(DetectReason reason) {
  switch (reason) {
    case DetectReason::kFound:
      return "found";
    case DetectReason::kEmptyCloud:
      return "empty cloud";
    case DetectReason::kInvalidModel:
      return "invalid model";
    case DetectReason::kInvalidOptions:
      return "invalid options";
    case DetectReason::kNoHypothesis:
      return "no hypothesis";
    case DetectReason::kNotConfirmed:
      return "not confirmed";
    case DetectReason::kNotLinked:
      return "parts not linked";
  }
  return "unknown";
}

ObjectDetectResult detect_object(const ObjectModel& model, std::span<const Eigen::Vector3d> points,
                                 const ObjectDetectOptions& options) {
  const Clock::time_point t_start = Clock::now();
  ObjectDetectResult result;
  if (!model_ok(model)) {
    result.reason = DetectReason::kInvalidModel;
    return result;
  }
  if (!options_ok(options)) {
    result.reason = DetectReason::kInvalidOptions;
    return result;
  }
  const Scan scan = prepare_scan(points, options, result);  // 5.1.1
  if (scan.cloud.empty()) {
    result.reason = DetectReason::kEmptyCloud;
    result.time.total_ms = ms_since(t_start);
    return result;
  }
  Clock::time_point t0 = Clock::now();
  const KdTree tree(scan.cloud);
  // The whole scan, plane included: lines of sight that pass a claimed surface mostly end on the
  // table.
  const OccupancyGrid occupancy(scan.whole(), occupancy_cell_mm(scan.cloud, tree));
  CoverageOptions cover = coverage_options(options, result.plane, scan.cloud, occupancy);
  // A stripe ranger's camera looks along another line than its laser (laser_shadow.hpp). The
  // table shades only what lies below it: the shadow is cast by the rest of the scan.
  const LaserShadow shadow(scan.cloud, cover.sensor, occupancy.cell_mm(), scan.whole());
  if (!shadow.empty()) cover.laser_shadow = &shadow;
  result.time.search_index_ms = ms_since(t0);
  // The scan's range noise, as the table shows it (0 without a plane: the floor alone).
  const double noise_mm = result.plane.removed() ? result.plane.plane.rms : 0.0;

  t0 = Clock::now();
  HypothesisContext ctx{scan.cloud, &tree, &options, {}, {}, std::nullopt, 0.0};
  if (options.rest_on_plane && cover.removed_plane) {
    ctx.table = cover.removed_plane;
    ctx.table_noise_mm = noise_mm;
    ctx.rests_on_table = model.parts.size() == 1;
  }
  Hypotheses hyps = search_parts(ctx, model, cover, noise_mm);  // 5.1.2
  result.hypotheses_evaluated = hyps.evaluated;
  result.time.hypotheses_ms = ms_since(t0);

  t0 = Clock::now();
  select_instances(ctx, model, cover, noise_mm, hyps, result);
  if (ctx.table) {
    for (DetectedInstance& inst : result.instances) set_on_table(model, *ctx.table, inst);
  }
  result.time.vote_ms = ms_since(t0);
  if (!result.instances.empty()) {
    result.reason = DetectReason::kFound;
  } else {
    explain_not_found(model, options, hyps, result);
  }
  result.time.total_ms = ms_since(t_start);
  return result;
}

}  // namespace rangefit
