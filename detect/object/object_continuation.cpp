#include "detect/object/object_continuation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rangefit {
namespace {

// Points of a sibling part with G below this are its own (the refinement's trim band).
constexpr double kSiblingGate = 1.6;

// The least width of the window in which a point counts as carrying on past a face, in bands.
constexpr double kMinWindowBands = 2.0;

// A point counts as past a face from this many bands (and 2 % of the size) beyond it. At two
// bands, lying look-alike boxes 7.7 and 12.6 % longer than the model at 0.77-0.81 mm noise (a
// band of 2.3-2.4 mm) reached 4-6 mm past its ends, no farther than the window began, and were
// taken for the box (pan-tilt object-free seeds 422 and 379).
constexpr double kPastBands = 1.5;

// The point spacing is taken from every kSpacingStride-th surface point, at most kSpacingSamples.
constexpr int kSpacingStride = 16;
constexpr std::size_t kSpacingSamples = 64;

// One way of extending the part: its sizes stretched by `stretch`, and how far out along the
// stretch a part-frame point is, in units of the part's size there (1: on the face being
// extended past).
struct Extension {
  Eigen::Vector3d stretch;
  enum Along { kZ, kX, kY, kRadial } along;
};

double outwards(const Superquadric& sq, const Eigen::Vector3d& q, Extension::Along along) {
  switch (along) {
    case Extension::kZ:
      return std::abs(q.z()) / sq.a3;
    case Extension::kX:
      return std::abs(q.x()) / sq.a1;
    case Extension::kY:
      return std::abs(q.y()) / sq.a2;
    case Extension::kRadial:
      return std::pow(std::pow(std::abs(q.x()) / sq.a1, 2.0 / sq.eps2) +
                          std::pow(std::abs(q.y()) / sq.a2, 2.0 / sq.eps2),
                      0.5 * sq.eps2);
  }
  return 0.0;
}

double size_along(const Superquadric& sq, Extension::Along along) {
  switch (along) {
    case Extension::kZ:
      return sq.a3;
    case Extension::kX:
      return sq.a1;
    case Extension::kY:
      return sq.a2;
    case Extension::kRadial:
      return std::min(sq.a1, sq.a2);
  }
  return 0.0;
}

// Which side of the part a point past one of its faces lies on, along the extension.
double side_of(const Eigen::Vector3d& q, Extension::Along along) {
  switch (along) {
    case Extension::kZ:
      return q.z();
    case Extension::kX:
      return q.x();
    case Extension::kY:
      return q.y();
    case Extension::kRadial:
      return 0.0;
  }
  return 0.0;
}

}  // namespace

Continuation surface_continuation(const Superquadric& sq, const Eigen::Isometry3d& T,
                                  std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                  const ContinuationOptions& o,
                                  std::span<const PlacedShape> explained) {
  Continuation c;
  if (!sq.valid() || points.empty() || sq.kx != 0.0 || sq.ky != 0.0) return c;
  std::vector<Extension> ext;
  const double r = 1.0 + o.reach;
  if (sq.eps1 <= kFlatExponent) {
    ext.push_back({{1.0, 1.0, r}, Extension::kZ});  // the side wall past the caps
    if (sq.eps2 <= kFlatExponent) {
      ext.push_back({{r, 1.0, 1.0}, Extension::kX});  // caps and sides past the side walls
      ext.push_back({{1.0, r, 1.0}, Extension::kY});
    } else {
      ext.push_back({{r, r, 1.0}, Extension::kRadial});  // the caps past the rim
    }
  }
  if (ext.empty()) return c;
  const SuperquadricMetric model(sq);
  std::vector<SuperquadricMetric> stretched;
  // Past the face by more than kPastBands bands and 2 % of the size (a noisy point by an edge,
  // or the edge of a part posed a millimetre off, is not past it), short of the stretched part's
  // own rounded end by twice the band. At 0.8 mm noise that left nothing of reach x 25 mm between
  // the two, and a box 18 % wider than the model carried on unseen: each extension reaches at
  // least far enough to leave kMinWindowBands bands between them.
  std::vector<double> past(ext.size()), reach(ext.size());
  double farthest = r;
  for (std::size_t k = 0; k < ext.size(); ++k) {
    const double size = size_along(sq, ext[k].along);
    past[k] = kPastBands * o.band_mm + 0.02 * size;
    reach[k] = std::max(r, 1.0 + (past[k] + (2.0 + kMinWindowBands) * o.band_mm) / size);
    for (int i = 0; i < 3; ++i) {
      if (ext[k].stretch[i] != 1.0) ext[k].stretch[i] = reach[k];
    }
    farthest = std::max(farthest, reach[k]);
  }
  for (const Extension& e : ext) {
    Superquadric s = sq;
    s.a1 *= e.stretch.x(), s.a2 *= e.stretch.y(), s.a3 *= e.stretch.z();
    stretched.emplace_back(s);
  }
  std::vector<SuperquadricMetric> sib;
  std::vector<Eigen::Isometry3d> sib_inv;
  for (const PlacedShape& p : explained) {
    sib.emplace_back(p.shape);
    sib_inv.push_back(p.T_world_part.inverse());
  }
  // The continuing points by extension and side (group 2 k for the face at -, 2 k + 1 at +),
  // with how far past the face they lie (mm); a few of the part's own surface points for the
  // scan's spacing.
  std::vector<std::pair<std::size_t, double>> carried;
  std::vector<std::uint32_t> own;
  std::vector<std::uint32_t> nbr;
  const double radius = farthest * Eigen::Vector3d(sq.a1, sq.a2, sq.a3).norm() + o.band_mm;
  tree.radius_search(T.translation(), radius, nbr);
  const double stride =
      std::max(1.0, static_cast<double>(nbr.size()) / static_cast<double>(o.max_points));
  const Eigen::Isometry3d inv = T.inverse();
  for (double f = 0.0; f < static_cast<double>(nbr.size()); f += stride) {
    const Eigen::Vector3d& p = points[nbr[static_cast<std::size_t>(f)]];
    if (o.table && o.table->normal.dot(p - o.table->point) < o.table_margin_mm) continue;
    bool sibling = false;
    for (std::size_t k = 0; k < sib.size() && !sibling; ++k) {
      sibling = sib[k].value(sib_inv[k] * p) < kSiblingGate;
    }
    if (sibling) continue;
    const Eigen::Vector3d q = inv * p;
    const double d = surface_distance(model, q);
    if (std::abs(d) <= o.band_mm) {
      if (c.surface++ % kSpacingStride == 0 && own.size() < kSpacingSamples) {
        own.push_back(nbr[static_cast<std::size_t>(f)]);
      }
      continue;
    }
    if (d < 0.0) continue;  // inside
    for (std::size_t k = 0; k < ext.size(); ++k) {
      const double u = outwards(sq, q, ext[k].along);
      const double size = size_along(sq, ext[k].along);
      // Past the face, short of the stretched part's own end, on its extended surface.
      if (u * size <= size || u * size > reach[k] * size - 2.0 * o.band_mm) continue;
      if (std::abs(surface_distance(stretched[k], q)) <= o.band_mm) {
        carried.emplace_back(2 * k + (side_of(q, ext[k].along) > 0.0), u * size - size - past[k]);
        break;
      }
    }
  }
  // Only what carries on from the face: a face's points past `past` count when the surface runs
  // on to them from the face without a gap wider than two point spacings (or the band). A
  // neighbouring object whose face stands level with the part's a few millimetres beyond it
  // extends the face just as well, but across a bare strip: a true box's neighbour 5.7 mm past its
  // edge, just beyond the margin, had counted as its own surface carrying on. Farther out a
  // continuing surface may be broken (a shadow across it) and still count.
  if (!carried.empty()) {
    const double gap =
        std::max(o.band_mm, 2.0 * median_neighbour_distance(points, tree, own).value_or(0.0));
    std::sort(carried.begin(), carried.end());
    for (std::size_t i = 0; i < carried.size();) {
      const std::size_t group = carried[i].first;
      // Nearer than the band past the face a point is the part's own surface.
      double run = o.band_mm - past[group / 2];
      bool broken = false;
      int beyond = 0;
      for (; i < carried.size() && carried[i].first == group; ++i) {
        const double v = carried[i].second;
        if (!broken) broken = v - run > gap;
        if (!broken) run = std::max(run, v);
        beyond += v > 0.0;
      }
      if (run > 0.0) c.continuing += beyond;
    }
  }
  if (c.surface > 0) c.share = static_cast<double>(c.continuing) / c.surface;
  return c;
}

}  // namespace rangefit
