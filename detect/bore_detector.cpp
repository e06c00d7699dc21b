#include "detect/bore_detector.hpp"

#include "detect/bore_stages.hpp"

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

}  // namespace

BoreResult detect_bore(const PointCloud& cloud, const BorePrior& prior, const BoreOptions& o) {
  bore::StageClock clock;
  BoreResult res;
  res.counts.input = cloud.size();
  if (!bore::valid_input(prior, o)) return fail(res, BoreReason::kBadPrior, clock);
  const bore::BoreFrame f = bore::bore_frame(prior, o);

  // 4.1.1 region of interest and normals.
  const BoreRegion region = bore::region_of_interest(cloud, f, o);
  res.counts.non_finite = region.non_finite;
  res.counts.stride = region.stride;
  res.counts.roi = region.roi.size() * region.stride;
  res.time_ms.roi = clock.lap();
  if (region.roi.empty()) return fail(res, BoreReason::kEmptyRoi, clock);
  const bore::RegionNormals normals = bore::region_normals(region, f, o);
  res.counts.normal_queries = normals.queries.size();
  res.counts.normals = normals.normals.kept;
  res.time_ms.normals = clock.lap();
  if (normals.normals.kept == 0) return fail(res, BoreReason::kDegenerateNormals, clock);

  // 4.1.2 Gaussian-image segmentation and the entrance plane.
  const bore::Segmentation seg = bore::segment(region, normals, f, prior, o);
  res.counts.plane = seg.plane.size();
  res.counts.wall = seg.walls.front().points.size();
  const pca::Plane plane = bore::entrance_plane(region, seg, f, o);
  res.time_ms.segmentation = clock.lap();
  if (!plane.valid) return fail(res, BoreReason::kNoPlane, clock);

  // 4.1.3-4.1.4 per wall: cylinder fit, notch re-fit, refinement, entrance.
  RefineInput base;
  base.cloud = cloud.points;
  base.region = &region;
  base.plane = plane;
  base.up = plane.normal.dot(f.view) < 0.0 ? Eigen::Vector3d(-plane.normal) : plane.normal;
  base.normal_radius = normals.radius;
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

}  // namespace rangefit
