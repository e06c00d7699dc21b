#include "detect/range_image.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace rangefit {
namespace {

// Directions more than ~84 degrees off the view axis are left out of the image.
constexpr double kMinAxisCosine = 0.1;
constexpr std::ptrdiff_t kMaxSide = 4096;

}  // namespace

RangeImage::RangeImage(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& viewpoint,
                       double points_per_pixel)
    : viewpoint_(viewpoint) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - viewpoint;
    if (d.allFinite() && d.norm() > 0.0) mean += d.normalized();
  }
  if (!(mean.norm() > 0.0) || !viewpoint.allFinite()) return;
  const Eigen::Vector3d axis = mean.normalized(), e1 = axis.unitOrthogonal();
  to_view_.row(0) = e1;
  to_view_.row(1) = axis.cross(e1);
  to_view_.row(2) = axis;
  // Image coordinates u = x/z, v = y/z in the view frame; their bounds give the image size.
  double umin = std::numeric_limits<double>::max(), vmin = umin, umax = -umin, vmax = -umin;
  std::size_t n = 0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = to_view_ * (p - viewpoint);
    if (!(q.z() > kMinAxisCosine * q.norm())) continue;
    umin = std::min(umin, q.x() / q.z()), umax = std::max(umax, q.x() / q.z());
    vmin = std::min(vmin, q.y() / q.z()), vmax = std::max(vmax, q.y() / q.z());
    ++n;
  }
  if (n == 0) return;
  const double area = std::max((umax - umin) * (vmax - vmin), 1e-12);
  double cell = std::sqrt(area * std::max(points_per_pixel, 1.0) / static_cast<double>(n));
  cell = std::max({cell, (umax - umin) / kMaxSide, (vmax - vmin) / kMaxSide});
  inv_cell_ = 1.0 / cell;
  u0_ = umin;
  v0_ = vmin;
  nu_ = static_cast<std::ptrdiff_t>((umax - umin) * inv_cell_) + 1;
  nv_ = static_cast<std::ptrdiff_t>((vmax - vmin) * inv_cell_) + 1;
  ranges_.assign(static_cast<std::size_t>(nu_ * nv_), std::numeric_limits<float>::infinity());
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - viewpoint;
    std::ptrdiff_t col = 0, row = 0;
    if (!pixel(d, &col, &row)) continue;
    float& r = ranges_[static_cast<std::size_t>(row * nu_ + col)];
    r = std::min(r, static_cast<float>(d.norm()));
  }
}

bool RangeImage::pixel(const Eigen::Vector3d& d, std::ptrdiff_t* col, std::ptrdiff_t* row) const {
  const Eigen::Vector3d q = to_view_ * d;
  if (!(q.z() > kMinAxisCosine * q.norm())) return false;
  const double u = (q.x() / q.z() - u0_) * inv_cell_, v = (q.y() / q.z() - v0_) * inv_cell_;
  if (!(u >= 0.0 && v >= 0.0 && u < static_cast<double>(nu_) && v < static_cast<double>(nv_))) {
    return false;
  }
  *col = static_cast<std::ptrdiff_t>(u);
  *row = static_cast<std::ptrdiff_t>(v);
  return true;
}

RayEvidence RangeImage::along(const Eigen::Vector3d& p, double tolerance_mm) const {
  if (ranges_.empty()) return RayEvidence::kUnknown;
  const Eigen::Vector3d d = p - viewpoint_;
  std::ptrdiff_t col = 0, row = 0;
  if (!pixel(d, &col, &row)) return RayEvidence::kUnknown;
  double first = std::numeric_limits<double>::infinity();
  for (std::ptrdiff_t r = std::max<std::ptrdiff_t>(row - 1, 0); r <= std::min(row + 1, nv_ - 1);
       ++r) {
    for (std::ptrdiff_t c = std::max<std::ptrdiff_t>(col - 1, 0); c <= std::min(col + 1, nu_ - 1);
         ++c) {
      first = std::min(first, static_cast<double>(ranges_[static_cast<std::size_t>(r * nu_ + c)]));
    }
  }
  if (std::isinf(first)) return RayEvidence::kUnknown;
  const double r = d.norm();
  if (first < r - tolerance_mm) return RayEvidence::kInFront;
  if (first > r + tolerance_mm) return RayEvidence::kBehind;
  return RayEvidence::kAt;
}

}  // namespace rangefit
