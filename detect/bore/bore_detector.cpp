#include "detect/bore/bore_detector.hpp"

#include "detect/bore/bore_stages.hpp"

namespace rangefit {

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
    case BoreReason::kBadShape:
      return "bad bore model (cone and ellipse at once, half-angle outside [0, 80 deg), "
             "cylinder radius not below the entrance radius, or radius2 without a major axis "
             "across the bore axis)";
    case BoreReason::kShapeFitFailed:
      return "cone or ellipse fit failed (too few points near the model, or the fit left it)";
  }
  return "unknown";
}

namespace {

BoreResult fail(BoreResult r, BoreReason reason, const bore::StageClock& clock) {
  r.found = false;
  r.reason = reason;
  r.time_ms.total = clock.total();
  return r;
}

// The RSF and refinement details of the (inner) wall fit.
void report_main_wall(const bore::WallFit& w, BoreResult& res) {
  res.counts.wall_final = w.wall_final;
  res.counts.axis_pairs = w.rsf.axis_pairs;
  res.counts.triangles = w.rsf.triangles;
  res.counts.refine_inliers = w.refine_inliers;
  res.rsf_radius = w.rsf.cylinder.radius;
  res.rsf_axis = w.rsf.cylinder.axis;
  res.second_fit = w.second_fit;
  res.refined = w.refined;
  if (w.sigma.valid) {
    res.sigma_axis = w.sigma.axis;
    res.sigma_offset = w.sigma.offset;
    res.sigma_radius = w.sigma.radius;
  }
}

BoreWallResult wall_result(const bore::WallFit& w, std::size_t wall_points) {
  BoreWallResult r;
  r.found = w.reason == BoreReason::kFound;
  r.reason = w.reason;
  r.entrance = w.entrance;
  r.axis = w.axis;
  r.radius = w.cylinder.radius;
  r.refined = w.refined;
  r.wall = wall_points;
  r.refine_inliers = w.refine_inliers;
  return r;
}

// A cone or elliptic bore: the model fit replaces the cylinder's RSF and refinement.
BoreResult shaped(BoreResult res, const RefineInput& base, const bore::Wall& wall,
                  const bore::BoreFrame& f, const BorePrior& prior, const BoreOptions& o,
                  bore::StageClock& clock) {
  const bore::ShapeWallFit w = bore::fit_shaped_wall(base, wall, f, prior, o);
  res.time_ms.refine = clock.lap();
  res.counts.axis_pairs = w.rsf.axis_pairs;
  res.counts.triangles = w.rsf.triangles;
  res.counts.refine_inliers = w.fit.inliers;
  res.rsf_radius = w.rsf.cylinder.radius;
  res.rsf_axis = w.rsf.cylinder.axis;
  if (w.reason != BoreReason::kFound) return fail(res, w.reason, clock);
  const BoreSurface& s = w.fit.surface;
  const SurfaceFitResult& fit = w.fit;
  BoreShape shape;
  shape.cone = s.cone;
  shape.half_angle = s.half_angle;
  shape.cylinder_radius = s.cylinder_radius;
  shape.radius2 = s.radius2;
  shape.major_axis = s.major;
  shape.sigma_radius = fit.sigma_radius;
  shape.sigma_half_angle = fit.sigma_half_angle;
  shape.sigma_cylinder_radius = fit.sigma_cylinder_radius;
  shape.sigma_radius2 = fit.sigma_radius2;
  shape.sigma_major_axis = fit.sigma_major;
  shape.sigma_entrance = fit.sigma_entrance;
  shape.sigma_axis = fit.sigma_axis;
  shape.rms = fit.rms;
  shape.iterations = fit.iterations;
  shape.seeded_by_rsf = w.seeded_by_rsf;
  res.shape = shape;
  res.entrance = s.entrance;
  res.axis = s.axis;
  res.radius = s.radius;
  res.plane_normal = base.up;
  res.refined = true;
  res.found = true;
  res.reason = BoreReason::kFound;
  res.time_ms.total = clock.total();
  return res;
}

// The whole pipeline; the workspace (nullptr: none) lends the call its memory.
BoreResult bore_pipeline(const PointCloud& cloud, const BorePrior& prior, const BoreOptions& o,
                         BoreWorkspace* workspace) {
  bore::StageClock clock;
  BoreResult res;
  res.counts.input = cloud.size();
  if (!bore::valid_input(prior, o)) return fail(res, BoreReason::kBadPrior, clock);
  if (!bore::valid_shape(prior, o)) return fail(res, BoreReason::kBadShape, clock);
  BoreArena arena(workspace);  // before the stages' buffers, which it outlives
  std::pmr::memory_resource* mr = arena.resource();
  const bore::BoreFrame f = bore::bore_frame(prior, o, mr);

  // 4.1.1 region of interest and normals.
  const BoreRegion region = bore::region_of_interest(cloud, f, o, mr);
  res.counts.non_finite = region.non_finite;
  res.counts.stride = region.stride;
  res.counts.roi = region.roi.size() * region.stride;
  res.time_ms.roi = clock.lap();
  if (region.roi.empty()) return fail(res, BoreReason::kEmptyRoi, clock);
  const bore::RegionNormals normals = bore::region_normals(region, f, o, mr);
  res.counts.normal_queries = normals.queries.size();
  res.counts.normals = normals.normals.kept;
  res.time_ms.normals = clock.lap();
  if (normals.normals.kept == 0) return fail(res, BoreReason::kDegenerateNormals, clock);

  // 4.1.2 Gaussian-image segmentation and the entrance plane.
  const bore::Segmentation seg = bore::segment(region, normals, f, prior, o, mr);
  res.counts.plane = seg.plane.size();
  res.counts.wall = seg.walls.front().points.size();
  const pca::Plane plane = bore::entrance_plane(region, seg, f, o, mr);
  res.time_ms.segmentation = clock.lap();
  if (!plane.valid) return fail(res, BoreReason::kNoPlane, clock);

  // 4.1.3-4.1.4 per wall: cylinder fit, notch re-fit, refinement, entrance.
  RefineInput base;
  base.cloud = cloud.points;
  base.region = &region;
  base.plane = plane;
  base.up = plane.normal.dot(f.view) < 0.0 ? Eigen::Vector3d(-plane.normal) : plane.normal;
  base.normal_radius = normals.radius;
  base.mr = mr;
  if (bore::has_shape(prior)) return shaped(res, base, seg.walls.front(), f, prior, o, clock);
  const auto fit = [&](std::size_t k) {
    return bore::fit_wall(base, seg.walls[k], f.targets[k], f, prior, o, clock, res.time_ms);
  };
  const bore::WallFit main = fit(0);
  report_main_wall(main, res);
  if (f.targets.size() > 1) res.outer = wall_result(fit(1), seg.walls[1].points.size());
  if (main.reason != BoreReason::kFound) return fail(res, main.reason, clock);
  res.entrance = main.entrance;
  res.axis = main.axis;
  res.radius = main.cylinder.radius;
  res.plane_normal = base.up;
  res.found = true;
  res.reason = BoreReason::kFound;
  res.time_ms.total = clock.total();
  return res;
}

}  // namespace

BoreResult detect_bore(const PointCloud& cloud, const BorePrior& prior, const BoreOptions& o) {
  return bore_pipeline(cloud, prior, o, nullptr);
}

BoreResult detect_bore(const PointCloud& cloud, const BorePrior& prior, const BoreOptions& o,
                       BoreWorkspace& workspace) {
  return bore_pipeline(cloud, prior, o, &workspace);
}

}  // namespace rangefit
