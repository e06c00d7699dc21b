#include "detect/common/laser_shadow.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "detect/common/occupancy_grid.hpp"

namespace rangefit {
namespace {

constexpr std::size_t kMaxBins = std::size_t{1} << 22;
constexpr std::size_t kExtentStride = 4;   // points read for the image's extent
constexpr std::size_t kSampleStride = 64;  // points read for the typical distances
constexpr double kColumnBins = 2.0;        // a column's width, in bins

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

bool sweep(const SensorView& v) {
  return v.kind == SensorView::Kind::kLinearSweep || v.kind == SensorView::Kind::kRotarySweep;
}

}  // namespace

LaserShadow::LaserShadow(std::span<const Eigen::Vector3d> points, const SensorView& view,
                         double bin_mm, std::span<const Eigen::Vector3d> beneath) {
  // Without a camera of its own the laser is the only eye, and its lines of sight are its rays.
  if (!sweep(view) || !valid(view) || view.camera_offset.squaredNorm() == 0.0 || !(bin_mm > 0.0) ||
      !std::isfinite(bin_mm)) {
    return;
  }
  view_ = view;
  mid_ = 0.5 * (view.sweep_min + view.sweep_max);
  // The fan's basis at mid_: `ahead` from its apex towards the points' centroid, in its plane.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  lo_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  hi_ = -lo_;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    centroid += p;
    lo_ = lo_.cwiseMin(p);
    hi_ = hi_.cwiseMax(p);
    ++n;
  }
  if (n == 0) return;
  centroid /= static_cast<double>(n);
  const SweepPose at_mid = sweep_pose(view, mid_);
  Eigen::Vector3d ahead = centroid - at_mid.apex;
  ahead -= ahead.dot(at_mid.plane_normal) * at_mid.plane_normal;
  if (!(ahead.norm() > 1e-9)) return;
  ahead_ = ahead.normalized();
  mid_apex_from_pivot_ = at_mid.apex - view.pivot;
  across_ = at_mid.plane_normal.cross(ahead_);
  int up = 0;
  ahead_.cwiseAbs().maxCoeff(&up);
  across_axes_ = {(up + 1) % 3, (up + 2) % 3};
  mark_columns(beneath.empty() ? points : beneath, bin_mm);

  // Bins about bin_mm wide at the points' typical range (and, turning, distance from the axis).
  // Two passes over the points, the rays computed again in the second: a list of them would
  // cost more in fresh memory than their few products.
  std::vector<double> ranges, radii;
  double s_lo = INFINITY, s_hi = -INFINITY, u_lo = INFINITY, u_hi = -INFINITY;
  // The extent from every kExtentStride-th point: a point past it is left out of the image.
  for (std::size_t i = 0; i < points.size(); i += kExtentStride) {
    const std::optional<Ray> r = points[i].allFinite() ? ray_of(points[i]) : std::nullopt;
    if (!r) continue;
    s_lo = std::min(s_lo, r->s), s_hi = std::max(s_hi, r->s);
    u_lo = std::min(u_lo, r->u), u_hi = std::max(u_hi, r->u);
    if (ranges.size() * kSampleStride <= i) {
      ranges.push_back(r->range);
      const Eigen::Vector3d q = points[i] - view.pivot;
      radii.push_back((q - q.dot(view.direction) * view.direction).norm());
    }
  }
  if (ranges.empty()) return;
  const double range = std::max(median(ranges), bin_mm);
  ds_ = view.kind == SensorView::Kind::kRotarySweep ? bin_mm / std::max(median(radii), bin_mm)
                                                    : bin_mm;
  du_ = bin_mm / range;
  const auto bins = [&](double extent, double step) {
    return static_cast<std::size_t>(std::floor(extent / step)) + 1;
  };
  while (bins(s_hi - s_lo, ds_) * bins(u_hi - u_lo, du_) > kMaxBins) ds_ *= 1.25, du_ *= 1.25;
  s0_ = s_lo, u0_ = u_lo;
  ns_ = bins(s_hi - s_lo, ds_), nu_ = bins(u_hi - u_lo, du_);
  // The second nearest return per bin: a lone outlier in the air before the surface (a few in a
  // thousand returns) would otherwise cast a shadow column down to it.
  constexpr float kNone = std::numeric_limits<float>::infinity();
  std::vector<float> first(ns_ * nu_, kNone);
  std::vector<std::uint32_t> first_index(ns_ * nu_, 0);
  range_.assign(ns_ * nu_, kNone);
  nearest_.assign(ns_ * nu_, 0);
  points_ = points;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::optional<Ray> r = points[i].allFinite() ? ray_of(points[i]) : std::nullopt;
    if (!r) continue;
    const std::optional<std::size_t> b = bin_of(r->s, r->u);
    if (!b) continue;
    const float at = static_cast<float>(r->range);
    const auto index = static_cast<std::uint32_t>(i);
    if (at < first[*b]) {
      range_[*b] = first[*b], nearest_[*b] = first_index[*b];
      first[*b] = at, first_index[*b] = index;
    } else if (at < range_[*b]) {
      range_[*b] = at, nearest_[*b] = index;
    }
  }
}

std::optional<LaserShadow::Ray> LaserShadow::ray_of(const Eigen::Vector3d& p) const {
  if (view_.kind == SensorView::Kind::kLinearSweep) {  // sweep_position and sweep_pose, inlined
    const double s =
        view_.plane_normal.dot(p - view_.origin) / view_.plane_normal.dot(view_.direction);
    if (!(s >= view_.sweep_min && s <= view_.sweep_max)) return std::nullopt;
    const Eigen::Vector3d v = p - view_.origin - s * view_.direction;
    const double forward = v.dot(ahead_);
    if (!(forward > 1e-9)) return std::nullopt;
    return Ray{s, v.dot(across_) / forward, v.norm()};
  }
  // A rotary sweep: turned back into the fan's frame at mid_. The apex turns about the pivot
  // with the fan, so p less the apex at s, turned by mid_ - s, is p turned about the pivot less
  // the apex at mid_ (Rodrigues' formula: one sine and cosine per ray).
  const std::optional<double> s = sweep_position(view_, p);
  if (!s) return std::nullopt;
  const Eigen::Vector3d& a = view_.direction;
  const Eigen::Vector3d q = p - view_.pivot;
  const double c = std::cos(mid_ - *s), sn = std::sin(mid_ - *s);
  const Eigen::Vector3d v =
      c * q + sn * a.cross(q) + (1.0 - c) * a.dot(q) * a - mid_apex_from_pivot_;
  const double forward = v.dot(ahead_);
  if (!(forward > 1e-9)) return std::nullopt;
  return Ray{*s, v.dot(across_) / forward, v.norm()};
}

std::optional<std::size_t> LaserShadow::bin_of(double s, double u) const {
  const double i = std::floor((s - s0_) / ds_), j = std::floor((u - u0_) / du_);
  if (!(i >= 0.0 && j >= 0.0 && i < static_cast<double>(ns_) && j < static_cast<double>(nu_))) {
    return std::nullopt;
  }
  return static_cast<std::size_t>(i) * nu_ + static_cast<std::size_t>(j);
}

void LaserShadow::mark_columns(std::span<const Eigen::Vector3d> points, double bin_mm) {
  const int a = across_axes_[0], b = across_axes_[1];
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) continue;
    lo = lo.cwiseMin(Eigen::Vector2d(p[a], p[b]));
    hi = hi.cwiseMax(Eigen::Vector2d(p[a], p[b]));
  }
  if (!(lo.x() <= hi.x())) return;
  column_lo_ = lo, column_hi_ = hi;
  column_mm_ = kColumnBins * bin_mm;
  const auto count = [&](int k) {
    return static_cast<std::size_t>(std::floor((hi[k] - lo[k]) / column_mm_)) + 1;
  };
  while (count(0) * count(1) > kMaxBins) column_mm_ *= 1.25;
  columns_ = {count(0), count(1)};
  column_seen_.assign(columns_[0] * columns_[1], false);
  for (const Eigen::Vector3d& p : points) {
    if (p.allFinite()) column_seen_[column_of({p[a], p[b]})] = true;
  }
}

std::size_t LaserShadow::column_of(const Eigen::Vector2d& q) const {
  const auto i = static_cast<std::size_t>((q.x() - column_lo_.x()) / column_mm_);
  const auto j = static_cast<std::size_t>((q.y() - column_lo_.y()) / column_mm_);
  return std::min(i, columns_[0] - 1) * columns_[1] + std::min(j, columns_[1] - 1);
}

bool LaserShadow::unlit(const Eigen::Vector3d& p) const {
  if (range_.empty() || !p.allFinite()) return false;
  // Something standing beneath p (along the axis nearest the fan's direction) would have hidden
  // the floor there or shown the laser some of its surface: a column with scan points in it
  // holds nothing unmeasured that reaches up to p. Past the scan's edge nothing was measured.
  const Eigen::Vector2d q(p[across_axes_[0]], p[across_axes_[1]]);
  if (!column_seen_.empty() && (q.array() >= column_lo_.array()).all() &&
      (q.array() <= column_hi_.array()).all() && column_seen_[column_of(q)]) {
    return false;
  }
  return !sweep_position(view_, p);
}

bool LaserShadow::shadowed(const Eigen::Vector3d& p, double margin_mm, const Casts& casts) const {
  if (range_.empty() || !p.allFinite()) return false;
  const std::optional<Ray> r = ray_of(p);
  if (!r) return false;
  // A bin between two profiles (a step wider than the bins) has no return of its own: the
  // profiles on either side stand for it.
  for (double ds : {0.0, -ds_, ds_}) {
    const std::optional<std::size_t> b = bin_of(r->s + ds, r->u);
    if (!b || !std::isfinite(range_[*b])) continue;
    return r->range > static_cast<double>(range_[*b]) + margin_mm &&
           (!casts || casts(points_[nearest_[*b]]));
  }
  return false;
}

double LaserShadow::first_shadowed(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                   double skip_mm, double step_mm, double margin_mm,
                                   const Casts& casts, double unlit_reach_mm) const {
  if (range_.empty() || !(step_mm > 0.0)) return -1.0;
  // Only within the points' box: nothing was measured, so nothing cast a shadow, outside it.
  const std::optional<BoxWalk> w = walk_in_box(from, to, skip_mm, lo_, hi_);
  if (!w) return -1.0;
  for (double t = w->begin; t <= w->end; t += step_mm) {
    const Eigen::Vector3d p = from + t * w->u;
    if ((t <= unlit_reach_mm && unlit(p)) || shadowed(p, margin_mm, casts)) return t;
  }
  // A line that leaves the box through a side, below the highest point measured, into space no
  // laser plane of the sweep holds: the sweep stopped short of whatever stands there. Through
  // the top or the bottom (the faces across the fan's direction), nothing measured stood.
  if (w->end < (to - from).norm() && w->end + step_mm <= unlit_reach_mm) {
    const Eigen::Vector3d exit = from + w->end * w->u;
    const int up = 3 - across_axes_[0] - across_axes_[1];
    const double tol = 1e-6 * (hi_ - lo_).norm();
    const bool side = std::abs(exit[up] - lo_[up]) > tol && std::abs(exit[up] - hi_[up]) > tol;
    const double past = w->end + step_mm;
    if (side && unlit(from + past * w->u)) return past;
  }
  return -1.0;
}

}  // namespace rangefit
