#include "detect/object/object_coverage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

namespace rangefit {
namespace {

// Surface seen more obliquely than ~75 degrees is no evidence either way: a scan samples it
// sparsely (or not at all), and its lines of sight graze the part's own measured surface.
constexpr double kMinIncidenceCosine = 0.25;
// ... but a scan point on surface seen up to ~87 degrees obliquely shows it is there (SampleJudge
// with_grazing).
constexpr double kMinGrazingCosine = 0.05;

// Exponents up to this make flat faces with rounded edges; the rest-on-table check takes those
// edges as sharp (this exponent).
constexpr double kFlatEdgeExponent = 0.5;
constexpr double kSharpExponent = 0.02;

// Eyes of an unknown sensor are this far away along their direction (mm): beyond any scene.
constexpr double kFarEye = 1e4;

// The inner rings by a flat end must show this share of their samples for the end to be judged.
constexpr double kEndReference = 0.8;

// A flat cap's rim is judged in this many sectors (a box's: one per edge of the face).
constexpr int kRimSectors = 4;

// What the scan says of one surface sample.
enum class Sample {
  kNoEvidence,   // by the table, outside the sweep, or not facing the sensor's eyes
  kHidden,       // facing them, but measured surface lies between
  kCovered,      // measurable, and a scan point lies near it
  kUncovered,    // measurable, no scan point near it
  kSeenThrough,  // measurable, and the laser went on past it to measured surface
  kGrazed,       // seen too obliquely to judge, but a scan point lies on it (with_grazing)
};

bool measurable(Sample v) {
  return v == Sample::kCovered || v == Sample::kUncovered || v == Sample::kSeenThrough;
}

// The samples of a part's outer rings (next to an edge) against as many rings farther in, for
// open_ends and open_rim: judged when the inner rings show the surface (kEndReference of their
// measurable samples covered), and then the share of the outer rings' measurable samples with no
// scan points near them; nothing when too few samples were measurable.
struct RingTally {
  int outer = 0, open = 0, inner = 0, inner_covered = 0;
  int outer_hidden = 0;  // outer samples that measured surface hides
  void add(Sample v, bool outer_ring) {
    const bool seen = measurable(v);
    if (outer_ring) {
      outer += seen;
      outer_hidden += v == Sample::kHidden;
      open += seen && v != Sample::kCovered;
    } else {
      inner += seen;
      inner_covered += v == Sample::kCovered;
    }
  }
  std::optional<double> open_share(int min_samples) const {
    if (outer < min_samples || inner < min_samples || inner_covered < kEndReference * inner) {
      return std::nullopt;
    }
    return static_cast<double>(open) / outer;
  }
};

// A ring strip's samples, rows (rings, outermost first) by columns (around the ring), tallied by
// RingTally once the samples at the edge of a hiding surface's shadow are taken out: a sample
// next to a hidden one is measurable by a hair's breadth of the occupancy grid, and the scan
// points that would cover it lie in the shadow's blurred edge (a wall's edge cells, the noise).
// Counted as uncovered, the few of them decide a strip of a dozen samples: a true box by a wall
// had 3 of its end's 11.
class RingStrip {
 public:
  RingStrip(int rows, int cols, bool cyclic)
      : rows_(rows), cols_(cols), cyclic_(cyclic), v_(static_cast<std::size_t>(rows * cols)) {}
  Sample& at(int row, int col) { return v_[static_cast<std::size_t>(row * cols_ + col)]; }
  // Rows [0, outer_rows) against [outer_rows, rows) (all rows when rows is 0). `whole_columns`:
  // a shadow anywhere in a sample's column or the next ones takes it out (a wide strip's shadow
  // edge runs across several rings).
  RingTally tally(int outer_rows, int rows = 0, bool whole_columns = false) {
    RingTally t;
    for (int r = 0; r < (rows > 0 ? rows : rows_); ++r) {
      for (int c = 0; c < cols_; ++c) {
        Sample v = at(r, c);
        if (r < outer_rows && v != Sample::kCovered && measurable(v) &&
            by_shadow(r, c, whole_columns ? rows_ : 1)) {
          v = Sample::kHidden;
        }
        t.add(v, r < outer_rows);
      }
    }
    return t;
  }

 private:
  bool by_shadow(int row, int col, int reach) {
    for (int dr = -reach; dr <= reach; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int r = row + dr;
        int c = col + dc;
        if (cyclic_) c = (c + cols_) % cols_;
        if (r < 0 || r >= rows_ || c < 0 || c >= cols_) continue;
        if (at(r, c) == Sample::kHidden) return true;
      }
    }
    return false;
  }
  int rows_, cols_;
  bool cyclic_;
  std::vector<Sample> v_;
};

// The open shares of a strip by an edge (RingTally::open_share) at two scales: `rings` rings
// over `strip` (a share of the size, from the edge inwards) against as many farther in; and all
// of those against `rings` rings at twice the spacing farther in, judged only where the first
// scale is not (its inner rings bare too: a part reaching past the surface's end by more than
// the strip) and its rings show a bare sample. sample(depth, column) judges the sample at that
// depth (share of the size from the edge) and column.
// `hidden`, when given: the first scale not judged, and at least min_samples of its outer
// rings' samples hidden by measured surface in front of them.
template <class JudgeAt>
std::array<std::optional<double>, 2> open_shares(int rings, int cols, bool cyclic, double strip,
                                                 int min_samples, JudgeAt&& sample,
                                                 bool* hidden = nullptr) {
  const double step = strip / rings;
  RingStrip s(3 * rings, cols, cyclic);
  const auto fill = [&](int first, int last) {
    for (int k = first; k < last; ++k) {
      const double depth =
          k < 2 * rings ? (k + 0.5) * step : 2.0 * strip + (k - 2 * rings + 0.5) * 2.0 * step;
      for (int j = 0; j < cols; ++j) s.at(k, j) = sample(depth, j);
    }
  };
  fill(0, 2 * rings);
  std::array<std::optional<double>, 2> out;
  const RingTally first = s.tally(rings, 2 * rings);
  out[0] = first.open_share(min_samples);
  if (hidden) *hidden = !out[0] && first.outer_hidden >= min_samples;
  if (out[0]) return out;
  bool bare = false;
  for (int k = 0; k < 2 * rings && !bare; ++k) {
    for (int j = 0; j < cols && !bare; ++j) {
      bare = measurable(s.at(k, j)) && s.at(k, j) != Sample::kCovered;
    }
  }
  if (!bare) return out;
  fill(2 * rings, 3 * rings);
  out[1] = s.tally(2 * rings, 0, true).open_share(min_samples);
  return out;
}

// Where the ray from the part centre along d leaves the part (G = 1), part frame. G is
// homogeneous of degree 2 without taper (G(s d) = s^2 G(d)); with taper it is still increasing
// along the ray (the tapered part is star-shaped about its centre), so bisection finishes it.
Eigen::Vector3d surface_along(const SuperquadricMetric& m, const Eigen::Vector3d& d) {
  const double g = m.value(d);
  if (!(g > 0.0)) return Eigen::Vector3d::Zero();
  double s = 1.0 / std::sqrt(g);
  if (m.model().kx == 0.0 && m.model().ky == 0.0) return s * d;
  double lo = 0.0, hi = s;
  while (m.value(hi * d) < 1.0 && hi < 1e6) hi *= 2.0;
  for (int i = 0; i < 40; ++i) {
    s = 0.5 * (lo + hi);
    (m.value(s * d) < 1.0 ? lo : hi) = s;
  }
  return 0.5 * (lo + hi) * d;
}

// Directions an unknown sensor is taken to look from: towards the points near the part's
// surface (they were seen, so the sensor is on their side) and up from the removed plane.
struct FarEyes {
  int count = 0;
  std::array<Eigen::Vector3d, 2> dir;
};

FarEyes far_eyes(const SuperquadricMetric& m, const Eigen::Isometry3d& T, double radius,
                 std::span<const Eigen::Vector3d> points, const KdTree& tree,
                 const std::optional<pca::Plane>& plane) {
  FarEyes e;
  std::vector<std::uint32_t> nbr;
  tree.radius_search(T.translation(), radius, nbr);
  const Eigen::Isometry3d inv = T.inverse();
  Eigen::Vector3d towards = Eigen::Vector3d::Zero();
  for (std::uint32_t i : nbr) {
    if (std::abs(m.value(inv * points[i]) - 1.0) < 0.2) towards += points[i] - T.translation();
  }
  if (towards.norm() < 1e-9) return e;
  towards.normalize();
  if (plane && plane->valid) e.dir[e.count++] = plane->normal.normalized();
  e.dir[e.count++] = towards;
  return e;
}

// Height of the posed part's lowest point above the plane (along its normal): the minimum over a
// coarse grid of the surface's parametrisation, then over finer grids around it. The coverage's
// samples alone leave a rounded bottom up to a few tenths of a millimetre above its lowest point,
// as much as the rest-on-table check must tell apart. `at`: the lowest point, part frame.
double lowest_height(const Superquadric& sq, const Eigen::Isometry3d& T, const pca::Plane& plane,
                     Eigen::Vector3d* at = nullptr) {
  constexpr int kEta = 16, kOmega = 32, kRefinements = 4;
  const Eigen::Vector3d n = T.linear().transpose() * plane.normal;  // part frame
  const double base = plane.normal.dot(T.translation() - plane.point);
  const auto height = [&](double eta, double omega) {
    eta = std::clamp(eta, -0.5 * std::numbers::pi, 0.5 * std::numbers::pi);
    return base + n.dot(surface_point(sq, eta, omega));
  };
  double d_eta = std::numbers::pi / kEta, d_omega = 2.0 * std::numbers::pi / kOmega;
  double best_eta = 0.0, best_omega = 0.0, best = INFINITY;
  for (int i = 0; i <= kEta; ++i) {
    for (int j = 0; j < kOmega; ++j) {
      const double eta = -0.5 * std::numbers::pi + i * d_eta,
                   omega = -std::numbers::pi + j * d_omega;
      const double h = height(eta, omega);
      if (h < best) best = h, best_eta = eta, best_omega = omega;
    }
  }
  for (int r = 0; r < kRefinements; ++r) {
    d_eta *= 0.4, d_omega *= 0.4;
    const double e0 = best_eta, o0 = best_omega;
    for (int i = -2; i <= 2; ++i) {
      for (int j = -2; j <= 2; ++j) {
        const double h = height(e0 + i * d_eta, o0 + j * d_omega);
        if (h < best) best = h, best_eta = e0 + i * d_eta, best_omega = o0 + j * d_omega;
      }
    }
  }
  if (at) {
    *at = surface_point(sq, std::clamp(best_eta, -0.5 * std::numbers::pi, 0.5 * std::numbers::pi),
                        best_omega);
  }
  return best;
}

// The camera's line of sight is walked through the laser's shadow in steps of this many
// occupancy cells: a shadow that hides anything (a wall's, an overhang's) is many cells wide.
constexpr double kShadowStepCells = 2.0;

// What the scan says of a surface sample q (part frame) of the part posed at T.
class SampleJudge {
 public:
  SampleJudge(const SuperquadricMetric& m, const Eigen::Isometry3d& T,
              std::span<const Eigen::Vector3d> points, const KdTree& tree, const CoverageOptions& o,
              double tol, const FarEyes& far)
      : m_(m),
        T_(T),
        points_(points),
        tree_(tree),
        o_(o),
        tol_(tol),
        far_(far),
        // Lines of sight start this far from the surface: its own points and its pose error stay
        // out (along an oblique line of sight, farther from the sample).
        clearance_(o.occupancy ? tol + o.occupancy->cell_mm() : tol),
        to_part_(T.inverse()),
        // G grows with the square of the radial scale: this is `tol` outside the smallest size.
        own_surface_(std::pow(1.0 + tol / m.model().min_size(), 2)),
        unlit_reach_(o.unlit_reach_of_max_size * m.model().max_size()),
        casts_([this](const Eigen::Vector3d& w) { return m_.value(to_part_ * w) > own_surface_; }) {
  }

  SampleJudge(const SampleJudge&) = delete;  // casts_ holds `this`
  SampleJudge& operator=(const SampleJudge&) = delete;

  Sample operator()(const Eigen::Vector3d& q) { return judge(q, kMinIncidenceCosine); }

  // The same, and kGrazed where that is no evidence because the sample is seen more obliquely
  // than kMinIncidenceCosine allows, but not more than kMinGrazingCosine, and a scan point lies
  // on it. Grazed surface is sampled sparsely, so a bare sample says nothing, but a point on it
  // does: a standing box under the pan-tilt head, its top mostly under an overhang, showed 7
  // judgeable samples of 200, and 31 more on a flank it grazed, each with a point.
  Sample with_grazing(const Eigen::Vector3d& q) {
    const Sample v = judge(q, kMinIncidenceCosine);
    if (v != Sample::kNoEvidence) return v;
    return judge(q, kMinGrazingCosine) == Sample::kCovered ? Sample::kGrazed : Sample::kNoEvidence;
  }

 private:
  Sample judge(const Eigen::Vector3d& q, double min_incidence) {
    Eigen::Vector3d grad;
    m_.value_and_gradient(q, grad);
    if (grad.squaredNorm() == 0.0) return Sample::kNoEvidence;
    const Eigen::Vector3d p = T_ * q;
    if (o_.removed_plane && o_.removed_plane->valid) {
      const double h = o_.removed_plane->normal.dot(p - o_.removed_plane->point);
      if (std::abs(h) < o_.plane_margin_mm + tol_) return Sample::kNoEvidence;
    }
    Eyes eyes;
    if (o_.sensor.kind != SensorView::Kind::kUnknown) {
      eyes = sensor_eyes(o_.sensor, p);
    } else {
      eyes.count = far_.count;
      for (int k = 0; k < far_.count; ++k) eyes.at[k] = p + kFarEye * far_.dir[k];
    }
    if (eyes.count == 0) return Sample::kNoEvidence;  // outside the sweep
    const Eigen::Vector3d un = (T_.linear() * grad).normalized();
    // The first eye (the laser, or the only one) must see the sample, and of the cameras any
    // one: those facing it, seen not too obliquely, are the ones that could have.
    std::array<double, 3> skip{};
    std::array<int, 3> eye{};
    int eyes_facing = 0;
    for (int k = 0; k < eyes.count; ++k) {
      const double incidence = un.dot((eyes.at[k] - p).normalized());
      // In the part's own shadow, or seen too obliquely to judge.
      if (incidence <= min_incidence) {
        if (k == 0) return Sample::kNoEvidence;
        continue;
      }
      skip[eyes_facing] = clearance_ / incidence;
      eye[eyes_facing++] = k;
    }
    if (eyes.count > 1 && eyes_facing == 1) return Sample::kNoEvidence;  // no camera faces it
    const auto nearest_point = [&] {
      tree_.knn_search(p, 1, nbr_);
      return nbr_.empty() ? INFINITY : (points_[nbr_[0]] - p).norm();
    };
    // A camera's line of sight may also pass where the laser never reached (a wall's grazed
    // face, laser_shadow.hpp): the sample may be hidden there, unless what cast the shadow is the
    // part's own surface.
    if (o_.occupancy) {
      if (o_.occupancy->first_hit(p, eyes.at[0], skip[0]) >= 0.0) return Sample::kHidden;
      bool camera_clear = eyes_facing == 1;  // a single eye has no camera to clear
      bool camera_unblocked = camera_clear;  // no measured surface on a camera's line of sight
      for (int i = 1; i < eyes_facing && !camera_clear; ++i) {
        const Eigen::Vector3d& at = eyes.at[static_cast<std::size_t>(eye[i])];
        const bool unblocked = o_.occupancy->first_hit(p, at, skip[i]) < 0.0;
        camera_unblocked = camera_unblocked || unblocked;
        camera_clear = unblocked && (!o_.laser_shadow ||
                                     o_.laser_shadow->first_shadowed(
                                         p, at, skip[i], kShadowStepCells * o_.occupancy->cell_mm(),
                                         tol_, casts_, unlit_reach_) < 0.0);
      }
      // A line of sight through the laser's shadow alone is not known to be clear, but a scan
      // point at the sample says it was: the camera saw the lit spot there. A cone under an
      // overhang seen by a low camera across the overhang's shadow showed 1,641 points and not
      // one measurable sample without this.
      if (!camera_clear)
        return camera_unblocked && nearest_point() <= tol_ ? Sample::kCovered : Sample::kHidden;
    }
    const double nearest = nearest_point();
    if (nearest <= tol_) return Sample::kCovered;
    // The first eye (the laser, or the only one) lit everything along its ray until the first
    // surface: a measured cell beyond the sample means the light went through it. A sample
    // between scan lines (grazing surface, coarse step) is not: it has points within a cell.
    if (o_.occupancy && nearest > tol_ + o_.occupancy->cell_mm()) {
      const Eigen::Vector3d beyond = p + kFarEye * (p - eyes.at[0]).normalized();
      if (o_.occupancy->first_hit(p, beyond, skip[0]) >= 0.0) return Sample::kSeenThrough;
    }
    return Sample::kUncovered;
  }

  const SuperquadricMetric& m_;
  const Eigen::Isometry3d& T_;
  std::span<const Eigen::Vector3d> points_;
  const KdTree& tree_;
  const CoverageOptions& o_;
  double tol_;
  const FarEyes& far_;
  double clearance_;
  // The scan's surface on or inside the posed part casts no shadow over it (LaserShadow::Casts).
  Eigen::Isometry3d to_part_;
  double own_surface_;
  double unlit_reach_;
  LaserShadow::Casts casts_;
  std::vector<std::uint32_t> nbr_;
};

// The side wall by each flat end, densely: end_rings rings at even steps over end_strip of the
// half-length from the cap, and as many farther in. An end is judged when the inner rings show
// the side wall (at least kEndReference of their measurable samples covered): then the scan
// would have shown it on to the cap, and the share of the outer rings' measurable samples with
// no scan points near them is how much of the end is missing. A true part whose end the scan
// does not show for another reason (grazed, behind a wall) shows little of the inner rings
// either. The shares per end (-z, +z) at the first scale, then at the second; 0 where not
// judged. `hidden`: per end, not judged at the first scale because measured surface hides it
// (open_shares; false for a part without flat ends).
std::array<double, 4> open_ends(const Superquadric& sq, const CoverageOptions& o,
                                SampleJudge& judge, std::array<bool, 2>& hidden) {
  hidden = {false, false};
  std::array<double, 4> open_at{0.0, 0.0, 0.0, 0.0};
  if (sq.eps1 > kFlatEdgeExponent || sq.kx != 0.0 || sq.ky != 0.0 || o.end_rings <= 0) {
    return open_at;
  }
  for (double side : {-1.0, 1.0}) {
    const std::size_t end = side > 0.0 ? 1 : 0;
    const auto shares = open_shares(
        o.end_rings, o.end_ring_samples, true, o.end_strip, o.min_end_samples,
        [&](double depth, int j) {
          const double eta = side * std::asin(std::pow(std::max(1.0 - depth, 0.0), 1.0 / sq.eps1));
          const double omega = 2.0 * std::numbers::pi * (j + 0.5) / o.end_ring_samples;
          return judge(surface_point(sq, eta, omega));
        },
        &hidden[end]);
    open_at[end] = shares[0].value_or(0.0);
    open_at[2 + end] = shares[1].value_or(0.0);
  }
  return open_at;
}

// A point of a flat cap's rim ring at radial fraction rho and angle omega, part frame, for the
// cap at +-z of the part `sq` (its cross-section's own shape, so a box's rings are squares).
Eigen::Vector3d cap_ring_point(const Superquadric& sq, double side, double rho, double omega) {
  const double c = std::cos(omega), s = std::sin(omega);
  const double e = 2.0 / sq.eps2;
  const double f = std::pow(std::pow(std::abs(c), e) + std::pow(std::abs(s), e), -0.5 * sq.eps2);
  return {sq.a1 * rho * f * c, sq.a2 * rho * f * s, side * sq.a3};
}

// The rims of the part's flat caps, by sector (a box's sectors are its faces' edges): the outer
// rings over rim_strip of the cap's radius against as many rings farther in. A sector is judged
// when its inner rings show the cap (kEndReference of their measurable samples covered); then the
// scan would have shown the cap on to its edge, and the share of the outer rings' measurable
// samples with no scan points near them is how far the part's cap reaches past the face the
// scan shows. A part fitted by one corner to a look-alike standing a tenth narrower claims a
// strip of top face where the sensor saw none; a true part hidden by its edge (overhang, wall,
// shadow) shows its hiding surface in front of the strip (hidden, no evidence). The caps are the
// +-z ones, and for a part whose cross-section is flat-sided too (a box) those at +-x and +-y.
std::array<double, 2> open_rim(const Superquadric& sq, const CoverageOptions& o,
                               SampleJudge& judge) {
  std::array<double, 2> worst{0.0, 0.0};
  if (sq.eps1 > kFlatEdgeExponent || sq.kx != 0.0 || sq.ky != 0.0 || o.rim_rings <= 0) {
    return worst;
  }
  const bool boxy = sq.eps2 <= kFlatEdgeExponent;
  for (int axis = boxy ? 0 : 2; axis < 3; ++axis) {
    // Cap frame: its normal is part axis `axis`, its first in-plane axis the next one.
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const Eigen::Vector3d a(sq.a1, sq.a2, sq.a3);
    Superquadric cap = sq;
    cap.a1 = a[u], cap.a2 = a[v], cap.a3 = a[axis];
    if (axis != 2) cap.eps1 = cap.eps2 = std::max(sq.eps1, sq.eps2);
    for (double side : {-1.0, 1.0}) {
      for (int sector = 0; sector < kRimSectors; ++sector) {
        const auto shares = open_shares(
            o.rim_rings, o.rim_sector_samples, false, o.rim_strip, o.min_end_samples,
            [&](double depth, int j) {
              const double omega = 2.0 * std::numbers::pi *
                                   (sector - 0.5 + (j + 0.5) / o.rim_sector_samples) / kRimSectors;
              const Eigen::Vector3d c = cap_ring_point(cap, side, 1.0 - depth, omega);
              Eigen::Vector3d q;
              q[u] = c.x(), q[v] = c.y(), q[axis] = c.z();
              return judge(q);
            });
        worst[0] = std::max(worst[0], shares[0].value_or(0.0));
        worst[1] = std::max(worst[1], shares[1].value_or(0.0));
      }
    }
  }
  return worst;
}

}  // namespace

SurfaceCoverage surface_coverage(const Superquadric& sq, const Eigen::Isometry3d& T,
                                 std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                 const CoverageOptions& o, CoverageMeasures measures) {
  if (!sq.valid() || points.empty() || o.samples < 1) return {};
  const SuperquadricMetric m(sq);
  const double tol = std::max(o.tolerance_mm, o.tolerance_of_min_size * sq.min_size());
  const bool known = o.sensor.kind != SensorView::Kind::kUnknown;
  const FarEyes far =
      known ? FarEyes{} : far_eyes(m, T, 1.2 * sq.max_size(), points, tree, o.removed_plane);
  if (!known && far.count == 0) return {};
  SampleJudge judge(m, T, points, tree, o, tol, far);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  int facing = 0, measured = 0, covered = 0, seen_through = 0, grazed = 0;
  for (int i = 0; measures.surface && i < o.samples; ++i) {
    // Fibonacci sphere, stretched by the sizes: even in the normalised coordinates.
    const double z = 1.0 - (2.0 * i + 1.0) / o.samples;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    const Eigen::Vector3d d(sq.a1 * r * std::cos(phi), sq.a2 * r * std::sin(phi), sq.a3 * z);
    const Sample v = judge.with_grazing(surface_along(m, d));
    facing += v != Sample::kNoEvidence;
    measured += measurable(v);
    covered += v == Sample::kCovered;
    seen_through += v == Sample::kSeenThrough;
    grazed += v == Sample::kGrazed;
  }
  std::array<bool, 2> end_hidden{};
  const std::array<double, 4> open_at =
      measures.ends ? open_ends(sq, o, judge, end_hidden) : std::array<double, 4>{};
  const std::array<double, 2> rim =
      measures.rims ? open_rim(sq, o, judge) : std::array<double, 2>{};
  SurfaceCoverage c;
  double below = 0.0, lowest = INFINITY;
  if (measures.surface && o.removed_plane && o.removed_plane->valid) {
    // Sinking is judged on the model itself and standing above the table on its sharp hull: a
    // flat-faced part's rounded edges (eps 0.1) lie a few per cent inside the real object's
    // edges, so a box tilted onto an edge rests on the table while its model stands ~3 mm above.
    below = std::max(0.0, -lowest_height(sq, T, *o.removed_plane, &c.deepest_part));
    Superquadric sharp = sq;
    if (sharp.eps1 <= kFlatEdgeExponent) sharp.eps1 = kSharpExponent;
    if (sharp.eps2 <= kFlatEdgeExponent) sharp.eps2 = kSharpExponent;
    lowest = lowest_height(sharp, T, *o.removed_plane);
  }
  c.below_plane_mm = below;
  c.lowest_mm = std::isfinite(lowest) ? lowest : 0.0;
  c.min_size_mm = sq.min_size();
  c.max_size_mm = sq.max_size();
  c.facing = facing;
  c.grazed = grazed;
  c.open_end_at[0] = open_at[0], c.open_end_at[1] = open_at[1];
  c.end_hidden[0] = end_hidden[0], c.end_hidden[1] = end_hidden[1];
  c.open_end_far_at[0] = open_at[2], c.open_end_far_at[1] = open_at[3];
  c.open_end = *std::max_element(open_at.begin(), open_at.end());
  c.open_rim = rim[0];
  c.open_rim_far = rim[1];
  if (measured == 0) return c;
  c.measurable = measured;
  c.covered = static_cast<double>(covered) / measured;
  c.seen_through = static_cast<double>(seen_through) / measured;
  return c;
}

void take_edges(SurfaceCoverage& c, const SurfaceCoverage& edges) {
  c.open_end = edges.open_end;
  for (std::size_t end = 0; end < 2; ++end) {
    c.open_end_at[end] = edges.open_end_at[end];
    c.open_end_far_at[end] = edges.open_end_far_at[end];
    c.end_hidden[end] = edges.end_hidden[end];
  }
  c.open_rim = edges.open_rim;
  c.open_rim_far = edges.open_rim_far;
}

}  // namespace rangefit
