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
                         double bin_mm) {
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

bool LaserShadow::shadowed(const Eigen::Vector3d& p, double margin_mm, const Casts& casts) const {
  if (range_.empty()) return false;
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
                                   const Casts& casts) const {
  if (range_.empty() || !(step_mm > 0.0)) return -1.0;
  // Only within the points' box: nothing was measured, so nothing cast a shadow, outside it.
  const std::optional<BoxWalk> w = walk_in_box(from, to, skip_mm, lo_, hi_);
  if (!w) return -1.0;
  for (double t = w->begin; t <= w->end; t += step_mm) {
    if (shadowed(from + t * w->u, margin_mm, casts)) return t;
  }
  return -1.0;
}

}  // namespace rangefit
