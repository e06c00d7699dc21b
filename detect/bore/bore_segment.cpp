// 4.1.1 normals on the region and 4.1.2 the Gaussian-image segmentation and entrance plane.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "detect/bore/bore_stages.hpp"
#include "detect/common/angles.hpp"
#include "detect/common/spread_subset.hpp"

namespace rangefit::bore {
namespace {

// Plane through the points, refit once without those beyond `sigmas` rms (outliers, a rim).
pca::Plane robust_plane(std::span<const Eigen::Vector3d> pts, double sigmas,
                        std::pmr::memory_resource* mr) {
  pca::Plane plane = pca::fit_plane(pts);
  if (!plane.valid || !(sigmas > 0.0)) return plane;
  std::pmr::vector<Eigen::Vector3d> kept(mr);
  kept.reserve(pts.size());
  const double limit = std::max(sigmas * plane.rms, 1e-3);
  for (const auto& p : pts) {
    if (std::abs((p - plane.point).dot(plane.normal)) <= limit) kept.push_back(p);
  }
  const pca::Plane refit = pca::fit_plane(kept);
  return refit.valid ? refit : plane;
}

// Beyond the thesis: the entrance plane again from every region point read near the plane
// fitted to the (sub-sampled) plane normals, beyond where those normals start around the axis
// (their 2nd-percentile distance from the CAD axis: a rim, chamfer or rounding stays out as the
// normal test kept it out). Running moments, no copies: the plane's accuracy follows the point
// count, not the normal count.
pca::Plane plane_from_region(const BoreRegion& region, std::span<const Eigen::Vector3d> plane_pts,
                             pca::Plane plane, const Eigen::Vector3d& entrance,
                             const Eigen::Vector3d& axis, std::pmr::memory_resource* mr) {
  const auto rho2 = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - entrance;
    const double h = d.dot(axis);
    return d.squaredNorm() - h * h;
  };
  std::pmr::vector<double> r(mr);
  r.reserve(plane_pts.size());
  for (const auto& p : plane_pts) r.push_back(rho2(p));
  const auto k = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 50);
  std::nth_element(r.begin(), k, r.end());
  const double rho2_min = *k;
  const double limit = std::max(3.0 * plane.rms, 0.03);
  pca::Moments m;
  for (const std::uint32_t i : region.roi) {
    const Eigen::Vector3d& p = region.points[i];
    const Eigen::Vector3d d = p - plane.point;
    if (std::abs(d.dot(plane.normal)) <= limit && rho2(p) >= rho2_min) m.add(d);
  }
  if (m.count < 10) return plane;
  const pca::Eigen3 e = pca::eigen_symmetric(m.covariance());
  pca::Plane next;
  next.valid = true;
  next.point = plane.point + m.mean();
  next.normal = e.vectors.col(0);
  next.rms = std::sqrt(std::max(e.values(0), 0.0));
  return next;
}

// Cost-bounded queries: evenly spread by area (a small bore, fewer points than the budget,
// keeps every point); on a dense scan (more wall points than the budget) the ball that holds
// about normal_neighbours points at the measured density (points per occupied area near the
// plane, seen head-on) is enough for a normal and costs O(1), a sparse one keeps R.
void budgeted_queries(const BoreRegion& g, const BoreFrame& f, const BoreOptions& o,
                      RegionNormals& out, std::pmr::memory_resource* mr) {
  const SpreadSubset w =
      spread_subset(g.points, g.near_wall, f.entrance, f.roi_radius, o.normal_wall_budget, mr);
  const SpreadSubset e =
      spread_subset(g.points, g.near_plane, f.entrance, f.roi_radius, o.normal_plane_budget, mr);
  const SpreadSubset x =
      spread_subset(g.points, g.other, f.entrance, f.roi_radius, o.normal_plane_budget / 2, mr);
  out.queries.reserve(w.indices.size() + e.indices.size() + x.indices.size());
  out.queries.assign(w.indices.begin(), w.indices.end());
  out.queries.insert(out.queries.end(), e.indices.begin(), e.indices.end());
  out.queries.insert(out.queries.end(), x.indices.begin(), x.indices.end());
  if (w.cell > 0.0 && e.area > 0.0 && o.normal_neighbours > 0.0) {
    const double density = static_cast<double>(g.near_plane.size()) / e.area;
    out.radius =
        std::min(out.radius, std::sqrt(o.normal_neighbours / (std::numbers::pi * density)));
  }
}

// Where a normal sorts a point (eq. 4.5, 4.6): the plane, a blind bore's bottom, each wall
// target whose band holds it.
void sort_point(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const BoreFrame& f,
                const BorePrior& prior, const BoreOptions& o, Segmentation& s) {
  if (n.dot(f.n_cad) > std::cos(o.plane_angle_deg * kDeg)) {
    // Beyond the thesis: a blind bore's bottom (or a surface seen through the bore) faces
    // the sensor like the entrance plane but lies inside the bore: not the plane.
    const Eigen::Vector3d d = p - prior.entrance;
    const double h = d.dot(f.a_cad);
    const double bottom_rho = 0.8 * prior.radius;
    if (d.squaredNorm() - h * h >= bottom_rho * bottom_rho) {
      s.plane.push_back(p);
    } else {
      s.walls.front().bottom.push_back(p);
    }
    return;
  }
  if (!(std::abs(n.dot(f.a_cad)) < std::sin(o.wall_angle_deg * kDeg))) return;
  // Beyond the thesis: a bore wall faces its axis, a pipe's outer wall away from it. With a
  // known view, a wall normal facing the wrong way is a neighbouring bore's wall or the other
  // wall of a pipe and is dropped; without one the sign is ambiguous, and the walls are told
  // apart by their distance from the CAD axis alone (radius clustering: each target's band
  // ends half-way to the other wall). Normals are turned toward the axis.
  Eigen::Vector3d to_axis = prior.entrance - p;
  to_axis -= to_axis.dot(f.a_cad) * f.a_cad;
  const double rho = to_axis.norm();
  const bool faces_axis = n.dot(to_axis) > 0.0;
  const bool oriented_view = o.view_dir || o.sensor_position;
  for (std::size_t k = 0; k < f.targets.size(); ++k) {
    const WallTarget& w = f.targets[k];
    if (rho > w.rho_hi || rho < w.rho_lo) continue;
    if (oriented_view && faces_axis != w.inner) continue;
    s.walls[k].points.push_back(p);
    s.walls[k].normals.push_back(faces_axis ? n : Eigen::Vector3d(-n));
  }
}

}  // namespace

RegionNormals region_normals(const BoreRegion& region, const BoreFrame& f, const BoreOptions& o,
                             std::pmr::memory_resource* mr) {
  RegionNormals out(mr);
  out.radius = f.normal_radius;
  if (o.cost_bounded) {
    budgeted_queries(region, f, o, out, mr);
  } else {
    out.queries.assign(region.roi.begin(), region.roi.end());
  }
  if (!(o.normal_keep >= 1.0)) out.queries = subsample_evenly(out.queries, o.normal_keep, mr);
  NormalOptions no;
  no.radius = out.radius;
  no.max_centroid_offset = o.max_centroid_offset;
  no.min_neighbours = o.min_neighbours;
  no.view_dir = f.view;
  no.sensor_position = o.sensor_position;
  // Exact R-neighbourhoods from a grid binned along the view, for organised and unorganised
  // scans alike (faster than the k-d tree or the scan-grid windows, and never misses a
  // neighbour the way a fixed window can where the scan is denser than its median spacing).
  out.normals = estimate_normals_binned(region.points, out.queries, no, mr);
  return out;
}

Segmentation segment(const BoreRegion& region, const RegionNormals& n, const BoreFrame& f,
                     const BorePrior& prior, const BoreOptions& o,
                     std::pmr::memory_resource* mr) {
  Segmentation s(mr);
  s.walls.reserve(f.targets.size());
  // Sized for the queries at once (a few thousand): no regrowth while sorting.
  s.plane.reserve(n.queries.size());
  for (std::size_t k = 0; k < f.targets.size(); ++k) {
    Wall& w = s.walls.emplace_back(mr);
    w.points.reserve(n.queries.size());
    w.normals.reserve(n.queries.size());
    w.bottom.reserve(k == 0 ? n.queries.size() : 0);
  }
  for (std::size_t i = 0; i < n.queries.size(); ++i) {
    const Eigen::Vector3d& normal = n.normals.normals[i];
    if (!normal.isZero()) sort_point(region.points[n.queries[i]], normal, f, prior, o, s);
  }
  return s;
}

pca::Plane entrance_plane(const BoreRegion& region, const Segmentation& s, const BoreFrame& f,
                          const BoreOptions& o, std::pmr::memory_resource* mr) {
  if (s.plane.size() < static_cast<std::size_t>(o.min_plane_points)) return {};
  const pca::Plane plane = robust_plane(s.plane, o.plane_inlier_sigmas, mr);
  if (!plane.valid || !o.cost_bounded) return plane;
  return plane_from_region(region, s.plane, plane, f.entrance, f.a_cad, mr);
}

}  // namespace rangefit::bore
