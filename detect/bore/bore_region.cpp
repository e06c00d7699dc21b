#include "detect/bore/bore_region.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit {
namespace {

// The probe reads every 16th scan point: a region of a few thousand points is counted to
// ~ +-10 %, enough to size a stride, at 1/16 of a full pass.
constexpr std::size_t kProbeStride = 16;

std::size_t count_within(std::span<const Eigen::Vector3d> cloud, const Eigen::Vector3d& c, double r,
                         std::size_t stride) {
  const double r2 = r * r;
  std::size_t n = 0;
  for (std::size_t i = 0; i < cloud.size(); i += stride) {
    n += (cloud[i] - c).squaredNorm() <= r2 ? 1 : 0;  // NaN compares false
  }
  return n;
}

}  // namespace

BoreRegion select_region(std::span<const Eigen::Vector3d> cloud, const RegionShape& s,
                         std::size_t budget, std::pmr::memory_resource* mr) {
  BoreRegion out(mr);
  if (budget > 0 && cloud.size() > budget) {
    const std::size_t probed = count_within(cloud, s.centre, s.roi_radius, kProbeStride);
    const std::size_t estimate = probed * kProbeStride;
    out.stride = std::max<std::size_t>(1, (estimate + budget - 1) / budget);
  }
  const std::size_t expect = cloud.size() / out.stride / 2 + 16;
  out.points.reserve(std::min(expect, budget > 0 ? 2 * budget : expect));
  out.source.reserve(out.points.capacity());
  out.roi.reserve(out.points.capacity());
  if (s.split) {  // no regrowth in the loop: each class may hold most of the region
    out.near_plane.reserve(out.points.capacity());
    out.near_wall.reserve(out.points.capacity() / 2);
    out.other.reserve(out.points.capacity() / 2);
  }
  const double pool2 = s.pool_radius * s.pool_radius, roi2 = s.roi_radius * s.roi_radius;
  const double hi2 = s.rho_hi * s.rho_hi, lo2 = 0.64 * s.rho_lo * s.rho_lo;
  for (std::size_t i = 0; i < cloud.size(); i += out.stride) {
    const Eigen::Vector3d& p = cloud[i];
    const Eigen::Vector3d d = p - s.centre;
    const double d2 = d.squaredNorm();
    if (!(d2 <= pool2)) {
      if (!p.allFinite()) ++out.non_finite;
      continue;
    }
    const auto k = static_cast<std::uint32_t>(out.points.size());
    out.points.push_back(p);
    out.source.push_back(static_cast<std::uint32_t>(i));
    if (d2 > roi2) continue;
    out.roi.push_back(k);
    if (!s.split) continue;
    const double h = d.dot(s.axis);
    const double rho2 = d2 - h * h;
    if (!(d.dot(s.plane_normal) < -s.below_margin)) {
      out.near_plane.push_back(k);
    } else if (rho2 <= hi2 && rho2 >= lo2) {
      out.near_wall.push_back(k);
    } else {
      out.other.push_back(k);
    }
  }
  return out;
}

}  // namespace rangefit
