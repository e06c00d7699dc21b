#include "detect/object/object_hypotheses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "detect/object/object_axial_slide.hpp"
#include "detect/object/pose_fit.hpp"
#include "detect/common/sensor_view.hpp"

namespace rangefit {
namespace {

constexpr std::size_t kMinPatchPoints = 8;
constexpr double kTrimPerMeasure = 3.0;
constexpr int kSeedRedraws = 8;
// Size evidence: a scaled fit whose mean square is below this share of the model's fit is
// clearly better.
constexpr double kClearlyBetter = 0.6;
constexpr int kSizeFitIterations = 8;

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform index in [0, n) from the generator state.
std::size_t uniform_index(std::uint64_t& state, std::size_t n) {
  return static_cast<std::size_t>(splitmix64(state) % static_cast<std::uint64_t>(n));
}

// How far a posed part reaches through the table plane (<= 0: not at all), by its inscribed
// ellipsoid, whose support along n is sqrt(sum (a_i n.R_i)^2): a part with eps <= 1 contains it,
// so a part whose ellipsoid sinks sinks at least as far. Tapered and pinched (eps > 1) parts are
// not judged (0).
double sinks_by(const Superquadric& part, const Eigen::Isometry3d& T, const pca::Plane& table) {
  if (part.eps1 > 1.0 || part.eps2 > 1.0 || part.kx != 0.0 || part.ky != 0.0) return 0.0;
  const Eigen::Vector3d n = T.linear().transpose() * table.normal;
  const double support = std::sqrt(std::pow(part.a1 * n.x(), 2) + std::pow(part.a2 * n.y(), 2) +
                                   std::pow(part.a3 * n.z(), 2));
  return support - table.normal.dot(T.translation() - table.point);
}

// RANSAC patch radius: the smallest size (5.1.2), wider for an elongated part (a shaft), whose
// small patches are nearly round bits of a thin cylinder and leave its axis to chance.
double patch_radius(const Superquadric& part) {
  const double elongation = part.max_size() / part.min_size();
  return part.min_size() * std::clamp(0.5 * elongation, 1.0, 2.5);
}

double verification_radius(const ObjectDetectOptions& o, const Superquadric& part) {
  return o.neighbourhood_factor * part.max_size();
}

// Buffers reused across the searches of one hypothesis.
struct Scratch {
  std::vector<std::uint32_t> indices;
  std::vector<double> values;
};

// Point filter for the parts already placed: true when one of them explains the point.
class ExplainedBy {
 public:
  ExplainedBy(std::span<const PlacedPart> parts, const ObjectDetectOptions& o)
      : gate_(1.0 + (o.refine_trim > 0.0 ? o.refine_trim : o.gamma)) {
    for (const PlacedPart& p : parts) {
      metrics_.emplace_back(p.shape);
      inverse_.push_back(p.T_world_part.inverse());
    }
  }
  bool operator()(const Eigen::Vector3d& p) const {
    for (std::size_t i = 0; i < metrics_.size(); ++i) {
      if (metrics_[i].value(inverse_[i] * p) < gate_) return true;
    }
    return false;
  }

 private:
  double gate_;
  std::vector<SuperquadricMetric> metrics_;
  std::vector<Eigen::Isometry3d> inverse_;
};

// Even subsample of the neighbourhood (capped), trimmed to points near or inside the surface.
// The k-d tree's order is deterministic for a given cloud, so no sort is needed for the result to
// depend only on the seed (sorting the indices took 14% of a detection).
std::vector<Eigen::Vector3d> refinement_points(const HypothesisContext& ctx,
                                               const Superquadric& part, const Eigen::Isometry3d& T,
                                               double trim, const ExplainedBy& explained,
                                               Scratch& scratch) {
  const ObjectDetectOptions& o = *ctx.options;
  ctx.tree->radius_search(T.translation(), verification_radius(o, part), scratch.indices);
  std::vector<std::uint32_t>& nbr = scratch.indices;
  const std::size_t cap = std::max<std::size_t>(o.max_refine_points, 16);
  if (nbr.size() > cap) {
    const double stride = static_cast<double>(nbr.size()) / static_cast<double>(cap);
    std::size_t kept = 0;
    for (double f = 0.0; f < static_cast<double>(nbr.size()); f += stride) {
      nbr[kept++] = nbr[static_cast<std::size_t>(f)];
    }
    nbr.resize(kept);
  }
  scratch.values.resize(nbr.size());
  if (trim > 0.0) SuperquadricMetric(part).values(T.inverse(), ctx.points, nbr, scratch.values);
  std::vector<Eigen::Vector3d> out;
  out.reserve(nbr.size());
  for (std::size_t k = 0; k < nbr.size(); ++k) {
    const Eigen::Vector3d& p = ctx.points[nbr[k]];
    if (trim > 0.0 && scratch.values[k] >= 1.0 + trim) continue;
    if (explained(p)) continue;
    out.push_back(p);
  }
  return out;
}

Eigen::Isometry3d refine(const HypothesisContext& ctx, const Superquadric& part,
                         Eigen::Isometry3d T, const ExplainedBy& explained, Scratch& scratch) {
  const ObjectDetectOptions& o = *ctx.options;
  PoseFitOptions fit;
  fit.max_iterations = o.iterations;
  double trim = o.refine_trim;
  for (int round = 0; round < o.refine_rounds; ++round) {
    const std::vector<Eigen::Vector3d> sel =
        refinement_points(ctx, part, T, trim, explained, scratch);
    if (sel.size() < kMinPatchPoints) break;
    const PoseFitResult r = fit_pose(part, sel, T, fit);
    if (!r.ok() || !(r.measure < r.initial_measure * (1.0 - 1e-3))) break;
    const double moved = (r.T_world_part.translation() - T.translation()).norm();
    T = r.T_world_part;
    // The band narrows with the fit: to 3 M (M: rms of G - 1), not below the surface band
    // gamma. Points of a neighbouring object that the first, wide band let in (a cone beside the
    // sphere) otherwise pull the part by millimetres.
    if (trim > 0.0) trim = std::min(trim, std::max(o.gamma, kTrimPerMeasure * r.measure));
    if (moved < 1e-3 * part.min_size()) break;
  }
  return T;
}

}  // namespace

double table_margin_mm(const ObjectDetectOptions& o, double min_size_mm, double noise_mm) {
  return std::max(o.plane_margin_mm, 0.1 * min_size_mm) + 3.0 * noise_mm;
}

double rest_tolerance_mm(const ObjectDetectOptions& o, double max_size_mm, double noise_mm) {
  return o.rest_noise_factor * noise_mm + o.rest_size_share * max_size_mm;
}

double height_sigma_mm(const Eigen::Isometry3d& T, const Eigen::Vector3d& q,
                       const Eigen::Vector3d& normal, const Eigen::Matrix<double, 6, 6>& cov) {
  // h = n . (R q + t): dh/d(dt) = n, and R <- R exp([w]x) moves R q by R (w x q), so
  // dh/dw = q x (R^T n).
  Eigen::Matrix<double, 6, 1> g;
  g.head<3>() = normal;
  g.tail<3>() = q.cross(T.linear().transpose() * normal);
  return std::sqrt(std::max(0.0, g.dot(cov * g)));
}

std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  std::uint64_t s = seed;
  s ^= splitmix64(s) + a * 0x632BE59BD9B4E019ull;
  s ^= splitmix64(s) + b * 0x8CB92BA72F3D8DD7ull;
  splitmix64(s);
  return s;
}

Eigen::Isometry3d refine_pose(const HypothesisContext& ctx, const Superquadric& part,
                              const Eigen::Isometry3d& T, std::span<const PlacedPart> explained) {
  Scratch scratch;
  return refine(ctx, part, T, ExplainedBy(explained, *ctx.options), scratch);
}

Eigen::Isometry3d slide_pose(const HypothesisContext& ctx, const Superquadric& part,
                             const Eigen::Isometry3d& T, const Eigen::Vector3d& prefer,
                             std::span<const PlacedPart> explained) {
  const ExplainedBy explained_by(explained, *ctx.options);
  AxialSlideOptions so;
  so.band_mm = std::max(1.0, 3.0 * ctx.table_noise_mm);
  so.table = ctx.table;
  so.table_margin_mm = table_margin_mm(*ctx.options, part.min_size(), ctx.table_noise_mm);
  so.prefer = prefer;
  return slide_to_wall(part, T, ctx.points, *ctx.tree, so,
                       [&](const Eigen::Vector3d& p) { return explained_by(p); });
}

PartScores verify_pose(const HypothesisContext& ctx, const Superquadric& part,
                       const Eigen::Isometry3d& T, std::span<const PlacedPart> explained) {
  const ObjectDetectOptions& o = *ctx.options;
  const ExplainedBy explained_by(explained, o);
  PartScores s;
  std::vector<std::uint32_t> nbr;
  ctx.tree->radius_search(T.translation(), verification_radius(o, part), nbr);
  std::vector<double> g(nbr.size());
  SuperquadricMetric(part).values(T.inverse(), ctx.points, nbr, g);
  const double trim =
      o.refine_trim > 0.0 ? 1.0 + o.refine_trim : std::numeric_limits<double>::max();
  double sum_sq = 0.0;
  std::size_t used = 0;
  for (std::size_t k = 0; k < nbr.size(); ++k) {
    if (!explained.empty() && explained_by(ctx.points[nbr[k]])) continue;
    if (g[k] < 1.0 - o.gamma) {
      ++s.interior;  // eq. 5.3
    } else if (g[k] < 1.0 + o.gamma) {
      ++s.surface;  // eq. 5.4
    }
    if (g[k] < trim) {
      sum_sq += (g[k] - 1.0) * (g[k] - 1.0);
      ++used;
    }
  }
  // Eq. 5.2 over the points the refinement fitted (all of them without trimming).
  s.measure = used > 0 ? std::sqrt(sum_sq / static_cast<double>(used))
                       : std::numeric_limits<double>::infinity();
  return s;
}

namespace {

// Mean squared distance (mm^2) of the points from the surface of the posed part.
double mean_square_distance(const Superquadric& part, const Eigen::Isometry3d& T,
                            std::span<const Eigen::Vector3d> points) {
  const SuperquadricMetric m(part);
  const Eigen::Isometry3d inv = T.inverse();
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) sum += std::pow(surface_distance(m, inv * p), 2);
  return points.empty() ? 0.0 : sum / static_cast<double>(points.size());
}

}  // namespace

SizeEvidence size_evidence(const HypothesisContext& ctx, const Superquadric& part,
                           const Eigen::Isometry3d& T, std::span<const PlacedPart> explained,
                           double du) {
  const ObjectDetectOptions& o = *ctx.options;
  Scratch scratch;
  const std::vector<Eigen::Vector3d> near =
      refinement_points(ctx, part, T, o.refine_trim > 0.0 ? o.refine_trim : o.gamma,
                        ExplainedBy(explained, o), scratch);
  SizeEvidence e;
  if (near.size() < 3 * kMinPatchPoints) return e;
  // The points on the surface, both sides alike: the band of the refinement keeps everything
  // inside but only a little outside, and what it lets in of a neighbouring object would ask for
  // a larger part.
  const SuperquadricMetric m1(part);
  const Eigen::Isometry3d inv = T.inverse();
  std::vector<double> d(near.size());
  for (std::size_t i = 0; i < near.size(); ++i)
    d[i] = std::abs(surface_distance(m1, inv * near[i]));
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  e.residual_mm = 1.4826 * sorted[sorted.size() / 2];
  const double gate = std::max(1.0, 3.0 * sorted[sorted.size() / 2]);
  std::vector<Eigen::Vector3d> sel;
  for (std::size_t i = 0; i < near.size(); ++i) {
    if (d[i] < gate) sel.push_back(near[i]);
  }
  if (sel.size() < 3 * kMinPatchPoints) return e;
  // Scaling the part by s scales G by u = 1 / s^2 (G is homogeneous of degree 2 without taper),
  // so G - 1 of a point is linear in u and steps of +-du in u ask the fits the same question
  // from both sides: the pose is re-fitted at u = 1 + du, 1, 1 - du, and a parabola in u through
  // the three misfits has its vertex at the size the points want. (Steps even in s would favour
  // the larger part.) The misfit is the mean squared distance from the surface in mm, not the
  // mean square of G - 1 the fits minimise: G - 1 is about twice the distance over the size
  // across a face, so it weighs a box's narrow faces and its steep rounded edges over the rest,
  // and the noise there made the true box want 3-4 % more than its size at 0.5 mm noise, as much
  // as a look-alike 7 % larger (1 % in mm).
  //
  // Three ways of being a different size are asked: all over, across the part's axis only (a1,
  // a2: a fatter can, an oblate ball) and along it only (a3: a taller can). For the last two G is
  // not homogeneous, but near u = 1 the parabola still places the size. The verdict is the one
  // farthest from the model among those the points determine.
  PoseFitOptions fit;
  fit.max_iterations = std::min(o.iterations, kSizeFitIterations);  // from a converged pose
  const PoseFitResult at_model = fit_pose(part, sel, T, fit);
  if (!at_model.ok()) return e;
  e.pose_covariance = at_model.covariance();
  const double ms1 = mean_square_distance(part, at_model.T_world_part, sel);
  enum Mode { kAll, kAcross, kAlong };
  for (Mode mode : {kAll, kAcross, kAlong}) {
    double ms[3] = {0.0, ms1, 0.0};
    bool ok = true;
    for (int k : {0, 2}) {
      const double s = 1.0 / std::sqrt(1.0 + (1 - k) * du);
      Superquadric scaled = part;
      if (mode != kAlong) scaled.a1 *= s, scaled.a2 *= s;
      if (mode != kAcross) scaled.a3 *= s;
      const PoseFitResult r = fit_pose(scaled, sel, T, fit);
      ok = ok && r.ok();
      ms[k] = mean_square_distance(scaled, r.T_world_part, sel);
    }
    if (!ok) continue;
    const double curvature = ms[0] - 2.0 * ms[1] + ms[2];
    double scale;
    if (std::min(ms[0], ms[2]) < kClearlyBetter * ms[1]) {
      // A step away from the model's size fits clearly better: the size the points want lies
      // beyond the step (a look-alike far off looks linear over it, not curved). "Clearly": one
      // face of a box seen alone can prefer a step along one axis a little.
      scale = 1.0 / std::sqrt(1.0 + (ms[0] < ms[2] ? du : -du));
    } else if (curvature > 0.05 * ms[1] && curvature > 1e-12) {
      const double u = 1.0 + du * 0.5 * (ms[2] - ms[0]) / curvature;
      if (!(u > 0.0)) continue;
      scale = 1.0 / std::sqrt(u);
    } else {
      continue;
    }
    if (!e.determined || std::abs(scale - 1.0) > std::abs(e.scale - 1.0)) e.scale = scale;
    e.determined = true;
  }
  return e;
}

PartHypothesis generate_hypothesis(const HypothesisContext& ctx, const Superquadric& part,
                                   std::uint64_t seed) {
  const ObjectDetectOptions& o = *ctx.options;
  PartHypothesis best;
  if (ctx.points.empty()) return best;
  std::uint64_t state = seed;
  Scratch scratch;
  std::vector<std::uint32_t>& nbr = scratch.indices;
  std::vector<Eigen::Vector3d> sample;
  MomentInitOptions init;
  init.short_iterations = o.init_iterations;
  init.full_iterations = o.iterations;
  init.viewpoint = o.viewpoint;
  const ExplainedBy none({}, o);
  const ExplainedBy set_aside(ctx.seed_excluded, o);
  const double table_margin = table_margin_mm(o, part.min_size(), ctx.table_noise_mm);
  // Of the moment starts, only those resting on the table are taken: a patch of a lying box's top
  // face fits the box standing through the table (its long axis along the normal) as well as the
  // box lying on it, and the trial would be lost.
  if (ctx.table) {
    init.admissible = [&](const Eigen::Isometry3d& T) {
      return sinks_by(part, T, *ctx.table) <= table_margin;
    };
  }
  double best_measure = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < o.trials; ++trial) {
    // A random seed point and a random patch within the smallest size parameter (5.1.2); seeds
    // on candidates already set aside are drawn again (a few times: they may be most points).
    std::size_t pick = uniform_index(state, ctx.points.size());
    for (int redraw = 0; redraw < kSeedRedraws && set_aside(ctx.points[pick]); ++redraw) {
      pick = uniform_index(state, ctx.points.size());
    }
    const Eigen::Vector3d& c = ctx.points[pick];
    ctx.tree->radius_search(c, patch_radius(part), nbr);
    if (nbr.size() < kMinPatchPoints) continue;
    const std::size_t want = std::min(nbr.size(), static_cast<std::size_t>(o.sample_points));
    sample.clear();
    for (std::size_t i = 0; i < want; ++i) {  // partial Fisher-Yates
      std::swap(nbr[i], nbr[i + uniform_index(state, nbr.size() - i)]);
      sample.push_back(ctx.points[nbr[i]]);
    }
    // With the sensor known but no single viewpoint (a sweep), the patch was seen from the eye
    // that lit its seed point: the part lies behind the patch from there. Both sides fit a flat
    // patch equally well, and a box set on the wrong side of its face stays there.
    if (!o.viewpoint) {
      const Eyes eyes = sensor_eyes(o.sensor, c);
      init.viewpoint = eyes.count > 0 ? std::optional<Eigen::Vector3d>(eyes.at[0]) : std::nullopt;
    }
    const PoseFitResult fit = fit_pose_from_moments(part, sample, init);
    if (!fit.ok()) continue;
    if (ctx.table && sinks_by(part, fit.T_world_part, *ctx.table) > table_margin) continue;
    Eigen::Isometry3d T = fit.T_world_part;
    double measure = fit.measure;
    if (o.refine_each_trial) {
      T = refine(ctx, part, T, none, scratch);
      measure = verify_pose(ctx, part, T).measure;
    }
    if (measure < best_measure) {
      best_measure = measure;
      best.valid = true;
      best.T_world_part = T;
    }
  }
  if (!best.valid) return best;
  if (!o.refine_each_trial) best.T_world_part = refine(ctx, part, best.T_world_part, none, scratch);
  best.scores = verify_pose(ctx, part, best.T_world_part);
  return best;
}

}  // namespace rangefit
