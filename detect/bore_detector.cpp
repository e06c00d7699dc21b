#include "detect/bore_detector.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "detect/bore_refine.hpp"
#include "detect/bore_region.hpp"
#include "detect/normals.hpp"
#include "detect/pca.hpp"
#include "detect/spread_subset.hpp"

namespace rangefit {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point& t0) {
  const Clock::time_point t1 = Clock::now();
  const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  t0 = t1;
  return ms;
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// Plane through the points, refit once without those beyond `sigmas` rms (outliers, a rim).
pca::Plane robust_plane(const std::vector<Eigen::Vector3d>& pts, double sigmas) {
  pca::Plane plane = pca::fit_plane(pts);
  if (!plane.valid || !(sigmas > 0.0)) return plane;
  std::vector<Eigen::Vector3d> kept;
  kept.reserve(pts.size());
  const double limit = std::max(sigmas * plane.rms, 1e-3);
  for (const auto& p : pts) {
    if (std::abs((p - plane.point).dot(plane.normal)) <= limit) kept.push_back(p);
  }
  const pca::Plane refit = pca::fit_plane(kept);
  return refit.valid ? refit : plane;
}

struct Wall {
  std::vector<Eigen::Vector3d> points, normals;
  std::vector<Eigen::Vector3d> bottom;  // points facing along the axis inside the bore
};

// Beyond the thesis: the entrance plane again from every full-resolution region point near the
// plane fitted to the (sub-sampled) plane normals, beyond where those normals start around the
// axis (their 2nd-percentile distance from the CAD axis: a rim, chamfer or rounding stays out
// as the normal test kept it out). Two passes of running moments, no copies: the plane's
// accuracy follows the point count, not the normal count.
pca::Plane plane_from_region(std::span<const Eigen::Vector3d> pool,
                             std::span<const std::uint32_t> roi,
                             const std::vector<Eigen::Vector3d>& plane_pts, pca::Plane plane,
                             const Eigen::Vector3d& entrance, const Eigen::Vector3d& axis) {
  const auto rho2 = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - entrance;
    const double h = d.dot(axis);
    return d.squaredNorm() - h * h;
  };
  std::vector<double> r;
  r.reserve(plane_pts.size());
  for (const auto& p : plane_pts) r.push_back(rho2(p));
  const auto k = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 50);
  std::nth_element(r.begin(), k, r.end());
  const double rho2_min = *k;
  {
    const double limit = std::max(3.0 * plane.rms, 0.03);
    pca::Moments m;
    for (const std::uint32_t i : roi) {
      const Eigen::Vector3d d = pool[i] - plane.point;
      if (std::abs(d.dot(plane.normal)) <= limit && rho2(pool[i]) >= rho2_min) m.add(d);
    }
    if (m.count < 10) return plane;
    const pca::Eigen3 e = pca::eigen_symmetric(m.covariance());
    pca::Plane next;
    next.valid = true;
    next.point = plane.point + m.mean();
    next.normal = e.vectors.col(0);
    next.rms = std::sqrt(std::max(e.values(0), 0.0));
    plane = next;
  }
  return plane;
}

BoreResult fail(BoreResult r, BoreReason reason, Clock::time_point start) {
  r.found = false;
  r.reason = reason;
  r.time_ms.total = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  return r;
}

}  // namespace

std::string_view to_string(BoreReason r) {
  switch (r) {
    case BoreReason::kFound:
      return "found";
    case BoreReason::kBadPrior:
      return "bad CAD prior or options (NaN, zero axis or radius <= 0)";
    case BoreReason::kEmptyRoi:
      return "no valid point within the region of interest";
    case BoreReason::kDegenerateNormals:
      return "no usable surface normal in the region";
    case BoreReason::kNoPlane:
      return "too few entrance-plane points to fit a plane";
    case BoreReason::kTooFewWallPoints:
      return "too few bore-wall points";
    case BoreReason::kFitFailed:
      return "cylinder fit failed";
    case BoreReason::kAxisParallelToPlane:
      return "fitted axis does not cross the entrance plane";
  }
  return "unknown";
}

namespace {

// One cylinder to fit: its CAD radius, which side of it faces the axis, and the band of
// distances from the CAD axis its wall points may have (radius clustering: a pipe's other wall
// lies outside the band, half the wall thickness away).
struct WallTarget {
  double radius = 0.0;
  bool inner = true;  // concave bore wall (faces the axis); false: a pipe's convex outer wall
  double rho_lo = 0.0, rho_hi = 0.0;
};

std::vector<WallTarget> wall_targets(const BorePrior& prior, const BoreOptions& o) {
  const double r_in = prior.radius;
  const double r_out = prior.outer_radius > r_in ? prior.outer_radius : 0.0;
  const double mid = 0.5 * (r_in + r_out);
  std::vector<WallTarget> t;
  if (o.walls != BoreWalls::kOuter) {
    const double hi = (1.0 + o.wall_band) * r_in;
    t.push_back({r_in, true, 0.0, r_out > 0.0 ? std::min(hi, mid) : hi});
  }
  if (o.walls != BoreWalls::kInner) {
    const double r = r_out > 0.0 ? r_out : r_in;
    t.push_back({r, false, r_out > 0.0 ? mid : (1.0 - o.wall_band) * r, (1.0 + o.wall_band) * r});
  }
  return t;
}

struct WallFit {
  BoreReason reason = BoreReason::kFitFailed;
  Cylinder cylinder;
  RsfResult rsf;
  bool second_fit = false, refined = false;
  std::size_t wall_final = 0, refine_inliers = 0;
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ();
};

// 4.1.3 and 4.1.4 for one wall: the sequential cylinder fit, the notch re-fit, the refinement
// on the region points near the cylinder and the entrance where the axis meets the plane.
WallFit fit_wall(const RefineInput& base, const Wall& wall, const Eigen::Vector3d& view,
                 const Eigen::Vector3d& a_cad, const BorePrior& prior, double r_cad,
                 const BoreOptions& o, std::uint64_t seed, Clock::time_point& t, BoreTimes& times) {
  WallFit w;
  const std::size_t min_wall = static_cast<std::size_t>(std::max(o.min_wall_points, 3));
  if (wall.points.size() < min_wall) {
    w.reason = BoreReason::kTooFewWallPoints;
    return w;
  }
  // 4.1.3 sequential cylinder fit, then 4.1.4: drop notch points beyond 1.03 r and fit again.
  RsfResult rsf =
      fit_cylinder_rsf(wall.points, wall.normals, a_cad, prior.entrance, r_cad, o.rsf, seed);
  if (rsf.status != RsfStatus::kOk) {
    times.rsf += ms_since(t);
    return w;
  }
  Wall inner;
  for (std::size_t i = 0; i < wall.points.size(); ++i) {
    if (axis_distance(rsf.cylinder, wall.points[i]) <= o.notch_ratio * rsf.cylinder.radius) {
      inner.points.push_back(wall.points[i]);
      inner.normals.push_back(wall.normals[i]);
    }
  }
  if (inner.points.size() < wall.points.size() && inner.points.size() >= min_wall) {
    const RsfResult second = fit_cylinder_rsf(inner.points, inner.normals, a_cad,
                                              rsf.cylinder.point, r_cad, o.rsf, seed + 1);
    if (second.status == RsfStatus::kOk) {
      rsf = second;
      w.second_fit = true;
      w.wall_final = inner.points.size();
    }
  }
  if (!w.second_fit) w.wall_final = wall.points.size();
  w.rsf = rsf;
  times.rsf += ms_since(t);

  // Beyond the thesis: geometric least squares on the region points near the RSF cylinder.
  // Every region point within the band counts, not only those whose normal passed eq. 4.6
  // (as PCL's fit does): the Gaussian image keeps a few hundred wall points, the band about
  // twice as many, and the axis error on the benchmark scan drops from 0.17 to 0.04 deg.
  Cylinder cyl = rsf.cylinder;
  if (o.refine) {
    RefineInput in = base;
    in.wall = wall.points;
    in.bottom = wall.bottom;
    const RefineOutcome r = refine_wall(in, cyl, o);
    w.refine_inliers = r.inliers;
    // Accept only a refinement that stays near the RSF answer (guards a runaway on bad data).
    if (r.lsf.iterations > 0 && std::abs(r.lsf.cylinder.radius - cyl.radius) < 0.2 * cyl.radius &&
        std::abs(r.lsf.cylinder.axis.dot(cyl.axis)) > std::cos(5.0 * kDeg)) {
      cyl = r.lsf.cylinder;
      w.refined = true;
    }
  }
  w.cylinder = cyl;
  times.refine += ms_since(t);

  // 4.1.4 entrance: the axis meets the entrance plane; axis out of the bore, toward the sensor.
  Eigen::Vector3d axis = cyl.axis.normalized();
  if (o.sensor_position ? axis.dot(*o.sensor_position - cyl.point) < 0.0 : axis.dot(view) < 0.0) {
    axis = -axis;
  }
  const pca::Plane& plane = base.plane;
  const double denom = plane.normal.dot(axis);
  if (std::abs(denom) < 0.1) {
    w.reason = BoreReason::kAxisParallelToPlane;
    return w;
  }
  const double s = plane.normal.dot(plane.point - cyl.point) / denom;
  w.entrance = cyl.point + s * axis;
  w.axis = axis;
  w.reason = BoreReason::kFound;
  times.entrance += ms_since(t);
  return w;
}

}  // namespace

BoreResult detect_bore(const PointCloud& cloud, const BorePrior& prior, const BoreOptions& o) {
  const Clock::time_point start = Clock::now();
  Clock::time_point t = start;
  BoreResult res;
  res.counts.input = cloud.size();
  const Eigen::Vector3d plane_prior = prior.plane_normal.value_or(prior.axis);
  if (!finite(prior.entrance) || !finite(prior.axis) || !finite(plane_prior) ||
      !std::isfinite(prior.radius) || !(prior.radius > 0.0) || !(prior.axis.norm() > 1e-9) ||
      !(plane_prior.norm() > 1e-9) || !(o.normal_radius > 0.0) || !(o.roi_radius_factor > 0.0) ||
      !std::isfinite(prior.outer_radius) ||
      (o.walls == BoreWalls::kBoth && !(prior.outer_radius > prior.radius)) ||
      (o.view_dir && !(finite(*o.view_dir) && o.view_dir->norm() > 1e-9)) ||
      (o.sensor_position && !finite(*o.sensor_position))) {
    return fail(res, BoreReason::kBadPrior, start);
  }
  // Orientation convention: everything toward the sensor (view direction, else plane normal).
  const Eigen::Vector3d view = o.view_dir ? o.view_dir->normalized() : plane_prior.normalized();
  Eigen::Vector3d n_cad = plane_prior.normalized();
  if (n_cad.dot(view) < 0.0) n_cad = -n_cad;
  Eigen::Vector3d a_cad = prior.axis.normalized();
  if (a_cad.dot(view) < 0.0) a_cad = -a_cad;
  const std::vector<WallTarget> targets = wall_targets(prior, o);
  double r_min = targets.front().radius, r_max = r_min;
  for (const auto& w : targets) {
    r_min = std::min(r_min, w.radius);
    r_max = std::max(r_max, w.radius);
  }

  // 4.1.1 region of interest (and the normal neighbourhood pool around it). Cost-bounded: the
  // region points are split into those near an expected wall and the rest (by their distance
  // from the CAD axis and their depth below the CAD plane), each thinned to its own budget.
  // Beyond the thesis: a patch as large as a small bore's radius is too curved for eq. 4.4.
  double normal_r = std::min(o.normal_radius, o.normal_radius_max_share * r_min);
  // A pipe's end face is only as wide as its wall: a larger patch straddles an edge everywhere
  // and eq. 4.4 would leave no plane (thesis fig. 4.33).
  if (prior.outer_radius > prior.radius) {
    normal_r = std::min(normal_r, 0.25 * (prior.outer_radius - prior.radius));
  }
  const double roi_r = o.roi_radius_factor * r_max;
  const double pool_r = roi_r + normal_r;
  double rho_lo = 1e300, rho_hi = 0.0;
  for (const auto& w : targets) {
    rho_lo = std::min(rho_lo, w.rho_lo);
    rho_hi = std::max(rho_hi, w.rho_hi);
  }
  // Below the CAD plane by more than the prior's offset can explain: not the entrance plane.
  const double below_margin = std::max(0.1 * r_min, 0.5);
  RegionShape shape;
  shape.centre = prior.entrance;
  shape.axis = a_cad;
  shape.plane_normal = n_cad;
  shape.roi_radius = roi_r;
  shape.pool_radius = pool_r;
  shape.rho_lo = rho_lo;
  shape.rho_hi = rho_hi;
  shape.below_margin = below_margin;
  shape.split = o.cost_bounded;
  const BoreRegion region =
      select_region(cloud.points, shape, o.cost_bounded ? o.region_budget : 0);
  const std::span<const Eigen::Vector3d> pts = region.points;
  const std::span<const std::uint32_t> roi = region.roi;
  const auto& near_wall = region.near_wall;
  const auto& near_plane = region.near_plane;
  const auto& other = region.other;
  res.counts.non_finite = region.non_finite;
  res.counts.stride = region.stride;
  res.counts.roi = roi.size() * region.stride;
  res.time_ms.roi = ms_since(t);
  if (roi.empty()) return fail(res, BoreReason::kEmptyRoi, start);

  // Normals on the (sub-sampled) ROI, neighbours from the full-resolution data.
  NormalOptions no;
  no.radius = normal_r;
  no.max_centroid_offset = o.max_centroid_offset;
  no.min_neighbours = o.min_neighbours;
  no.view_dir = view;
  no.sensor_position = o.sensor_position;
  std::vector<std::uint32_t> queries;
  if (o.cost_bounded) {
    // Evenly spread by area: a small bore (fewer points than the budget) keeps every point.
    SpreadSubset w = spread_subset(pts, near_wall, prior.entrance, roi_r, o.normal_wall_budget);
    SpreadSubset e = spread_subset(pts, near_plane, prior.entrance, roi_r, o.normal_plane_budget);
    SpreadSubset x = spread_subset(pts, other, prior.entrance, roi_r, o.normal_plane_budget / 2);
    queries = std::move(w.indices);
    queries.insert(queries.end(), e.indices.begin(), e.indices.end());
    queries.insert(queries.end(), x.indices.begin(), x.indices.end());
    // A dense scan (more wall points than the budget): the ball that holds about
    // normal_neighbours points at the measured density (points per occupied area near the
    // plane, seen head-on) is enough for a normal and costs O(1); a sparse one keeps R.
    if (w.cell > 0.0 && e.area > 0.0 && o.normal_neighbours > 0.0) {
      const double density = static_cast<double>(near_plane.size()) / e.area;
      no.radius =
          std::min(no.radius, std::sqrt(o.normal_neighbours / (std::numbers::pi * density)));
    }
  } else {
    queries.assign(roi.begin(), roi.end());
  }
  queries = subsample_evenly(queries, o.normal_keep);
  // Exact R-neighbourhoods from a grid binned along the view, for organised and unorganised
  // scans alike (faster than the k-d tree or the scan-grid windows, and never misses a
  // neighbour the way a fixed window can where the scan is denser than its median spacing).
  const NormalEstimate normals = estimate_normals_binned(pts, queries, no);
  res.counts.normal_queries = queries.size();
  res.counts.normals = normals.kept;
  res.time_ms.normals = ms_since(t);
  if (normals.kept == 0) return fail(res, BoreReason::kDegenerateNormals, start);

  // 4.1.2 Gaussian-image segmentation with the CAD prior (eq. 4.5, 4.6).
  const double cos_plane = std::cos(o.plane_angle_deg * kDeg);
  const double sin_wall = std::sin(o.wall_angle_deg * kDeg);
  std::vector<Eigen::Vector3d> plane_pts;
  std::vector<Wall> walls(targets.size());
  const bool oriented_view = o.view_dir || o.sensor_position;
  const double bottom_rho = 0.8 * prior.radius;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const Eigen::Vector3d& n = normals.normals[i];
    if (n.isZero()) continue;
    const Eigen::Vector3d& p = pts[queries[i]];
    if (n.dot(n_cad) > cos_plane) {
      // Beyond the thesis: a blind bore's bottom (or a surface seen through the bore) faces
      // the sensor like the entrance plane but lies inside the bore: not the plane.
      const Eigen::Vector3d d = p - prior.entrance;
      const double h = d.dot(a_cad);
      if (d.squaredNorm() - h * h >= bottom_rho * bottom_rho) {
        plane_pts.push_back(p);
      } else {
        walls.front().bottom.push_back(p);
      }
      continue;
    }
    if (!(std::abs(n.dot(a_cad)) < sin_wall)) continue;
    // Beyond the thesis: a bore wall faces its axis, a pipe's outer wall away from it. With a
    // known view, a wall normal facing the wrong way is a neighbouring bore's wall or the
    // other wall of a pipe and is dropped; without one the sign is ambiguous, and the walls
    // are told apart by their distance from the CAD axis alone (radius clustering: each
    // target's band ends half-way to the other wall). Normals are turned toward the axis.
    Eigen::Vector3d to_axis = prior.entrance - p;
    to_axis -= to_axis.dot(a_cad) * a_cad;
    const double rho = to_axis.norm();
    const bool faces_axis = n.dot(to_axis) > 0.0;
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const WallTarget& w = targets[k];
      if (rho > w.rho_hi || rho < w.rho_lo) continue;
      if (oriented_view && faces_axis != w.inner) continue;
      walls[k].points.push_back(p);
      walls[k].normals.push_back(faces_axis ? n : Eigen::Vector3d(-n));
    }
  }
  res.counts.plane = plane_pts.size();
  res.counts.wall = walls.front().points.size();
  pca::Plane plane = plane_pts.size() >= static_cast<std::size_t>(o.min_plane_points)
                         ? robust_plane(plane_pts, o.plane_inlier_sigmas)
                         : pca::Plane{};
  if (!plane.valid) {
    res.time_ms.segmentation = ms_since(t);
    return fail(res, BoreReason::kNoPlane, start);
  }
  if (o.cost_bounded) {
    plane = plane_from_region(pts, roi, plane_pts, plane, prior.entrance, a_cad);
  }
  res.time_ms.segmentation = ms_since(t);

  RefineInput base;
  base.cloud = cloud.points;
  base.region = &region;
  base.plane = plane;
  base.up = plane.normal.dot(view) < 0.0 ? Eigen::Vector3d(-plane.normal) : plane.normal;
  base.normal_radius = no.radius;
  const auto fit = [&](std::size_t k) {
    return fit_wall(base, walls[k], view, a_cad, prior, targets[k].radius, o, o.seed, t,
                    res.time_ms);
  };
  const WallFit main = fit(0);
  res.counts.wall_final = main.wall_final;
  res.counts.axis_pairs = main.rsf.axis_pairs;
  res.counts.triangles = main.rsf.triangles;
  res.counts.refine_inliers = main.refine_inliers;
  res.rsf_radius = main.rsf.cylinder.radius;
  res.rsf_axis = main.rsf.cylinder.axis;
  res.second_fit = main.second_fit;
  res.refined = main.refined;
  if (targets.size() > 1) {
    const WallFit outer = fit(1);
    BoreWallResult& w = res.outer.emplace();
    w.found = outer.reason == BoreReason::kFound;
    w.reason = outer.reason;
    w.entrance = outer.entrance;
    w.axis = outer.axis;
    w.radius = outer.cylinder.radius;
    w.refined = outer.refined;
    w.wall = walls[1].points.size();
    w.refine_inliers = outer.refine_inliers;
  }
  if (main.reason != BoreReason::kFound) return fail(res, main.reason, start);
  res.entrance = main.entrance;
  res.axis = main.axis;
  res.radius = main.cylinder.radius;
  res.plane_normal = plane.normal.dot(view) < 0.0 ? Eigen::Vector3d(-plane.normal) : plane.normal;
  res.found = true;
  res.reason = BoreReason::kFound;
  res.time_ms.total = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  return res;
}

}  // namespace rangefit
