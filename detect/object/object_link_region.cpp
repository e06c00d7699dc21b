#include "detect/object/object_link_region.hpp"

#include <algorithm>
#include <cmath>

namespace rangefit {
namespace {

// A part's bearing below this aims its axis at its sibling's centre (a mallet's shaft: 0).
constexpr double kAimedBearingRad = 0.1;

}  // namespace

std::vector<std::uint32_t> link_region(const PartLink& link, bool first, const Superquadric& part,
                                       const Eigen::Isometry3d& T_world_sibling, double margin_mm,
                                       std::span<const Eigen::Vector3d> points,
                                       const KdTree& tree) {
  const Eigen::Vector3d cq = T_world_sibling.translation();
  const Eigen::Vector3d zq = T_world_sibling.linear().col(2);
  const double d = link.distance_mm;
  const double bound = std::sqrt(part.a1 * part.a1 + part.a2 * part.a2 + part.a3 * part.a3);
  const double cross = std::max(part.a1, part.a2);
  std::vector<std::uint32_t> nbr;
  tree.radius_search(cq, d + bound + margin_mm, nbr);
  std::sort(nbr.begin(), nbr.end());
  std::vector<std::uint32_t> out;
  if (!link.bearing_rad) {  // a shell around the sibling's centre
    for (const std::uint32_t i : nbr) {
      if (std::abs((points[i] - cq).norm() - d) <= bound + margin_mm) out.push_back(i);
    }
    return out;
  }
  const double bq = (*link.bearing_rad)[first ? 1 : 0], bp = (*link.bearing_rad)[first ? 0 : 1];
  const bool aimed = bp < kAimedBearingRad && d > 0.0;
  const double along = d * std::cos(bq), ring = d * std::sin(bq);
  const Eigen::Vector3d e1 = zq.unitOrthogonal();
  // The places are symmetric about the sibling's axis: the one nearest a point lies in the
  // point's own half-plane through the axis, on either side along it.
  const auto near_place = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& out_dir,
                              double side) {
    const Eigen::Vector3d c = cq + side * along * zq + ring * out_dir;
    if (!aimed) return (x - c).norm() <= bound + margin_mm;
    const Eigen::Vector3d axis = (c - cq) / d, v = x - c;
    const double s = std::clamp(v.dot(axis), -part.a3, part.a3);
    return (v - s * axis).norm() <= cross + margin_mm;
  };
  for (const std::uint32_t i : nbr) {
    const Eigen::Vector3d v = points[i] - cq;
    const Eigen::Vector3d radial = v - v.dot(zq) * zq;
    const double rho = radial.norm();
    const Eigen::Vector3d out_dir = rho > 1e-9 ? Eigen::Vector3d(radial / rho) : e1;
    if (near_place(points[i], out_dir, 1.0) || near_place(points[i], out_dir, -1.0)) {
      out.push_back(i);
    }
  }
  return out;
}

}  // namespace rangefit
