#include "detect/bore/bore_refine.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rangefit {
namespace {

// Squared distance from the axis line (unit axis): no root per point.
double rho2(const Eigen::Vector3d& p, const Eigen::Vector3d& c, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d d = p - c;
  const double h = d.dot(axis);
  return d.squaredNorm() - h * h;
}

// The shell lo..hi around a cylinder (squared bounds).
struct Shell {
  Eigen::Vector3d point, axis;
  double lo2 = 0.0, hi2 = 0.0;
  Shell(const Cylinder& c, double lo, double hi)
      : point(c.point), axis(c.axis.normalized()), lo2(lo * lo), hi2(hi * hi) {}
  bool contains(const Eigen::Vector3d& p) const {
    const double r2 = rho2(p, point, axis);
    return r2 <= hi2 && r2 >= lo2;
  }
};

// Heights along the plane normal where wall points may lie: deeper than `below` under the
// plane, no higher than the segmented wall reaches (its 98th percentile) plus a share of R (a
// chamfer or rounded rim passes the band near the wall but not the normal test, which fails
// within about R of any edge), and above a blind bore's bottom where one is seen.
struct Heights {
  Eigen::Vector3d point, up;
  double top = 1e300, bottom = -1e300, below = 0.0;
  bool contains(const Eigen::Vector3d& p) const {
    const double h = (p - point).dot(up);
    return h <= top && h >= bottom && h < below;
  }
};

Heights wall_heights(const RefineInput& in, std::span<const Eigen::Vector3d> band,
                     const BoreOptions& o) {
  Heights w{in.plane.point, in.up};
  w.below = -o.refine_plane_margin;
  std::pmr::vector<double> h(in.mr);
  h.reserve(band.size());
  for (const auto& p : band) h.push_back((p - w.point).dot(w.up));
  const std::size_t k = (h.size() - 1) * 98 / 100;
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(k), h.end());
  w.top = h[k] + o.refine_above_wall * in.normal_radius;
  if (in.bottom.size() >= 10) {
    h.clear();
    for (const auto& p : in.bottom) h.push_back((p - w.point).dot(w.up));
    std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
    w.bottom = h[h.size() / 2] + o.refine_band;
  }
  return w;
}

// 3 robust sigmas (MAD) of the residuals |distance from the axis - r|, at least 0.01 mm.
double trim_limit(std::span<const Eigen::Vector3d> pts, const Cylinder& c,
                  std::pmr::memory_resource* mr) {
  std::pmr::vector<double> r(mr);
  r.reserve(pts.size());
  for (const auto& p : pts) r.push_back(std::abs(axis_distance(c, p) - c.radius));
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2), r.end());
  return std::max(3.0 * 1.4826 * r[r.size() / 2], 0.01);
}

// The band's points: their positions and, for the full-resolution fill, their cloud indices.
struct Band {
  explicit Band(std::pmr::memory_resource* mr) : points(mr), source(mr) {}
  std::pmr::vector<Eigen::Vector3d> points;
  std::pmr::vector<std::uint32_t> source;  // empty: no fill
};

Band collect_band(const RefineInput& in, const Cylinder& start, const BoreOptions& o,
                  Heights& heights) {
  const Shell shell(start, std::max(start.radius - o.refine_band, 0.0),
                    start.radius + o.refine_band);
  Band b(in.mr);
  b.points.reserve(in.wall.size());
  for (const auto& p : in.wall) {
    if (shell.contains(p)) b.points.push_back(p);
  }
  if (!o.refine_all_region_points || b.points.size() < 3) return b;
  heights = wall_heights(in, b.points, o);
  const BoreRegion& r = *in.region;
  b.points.clear();
  b.points.reserve(r.roi.size() / 2);
  const bool fill = o.cost_bounded && o.refine_full_resolution && r.stride > 1;
  if (fill) b.source.reserve(b.points.capacity());
  for (const std::uint32_t i : r.roi) {
    const Eigen::Vector3d& p = r.points[i];
    if (!heights.contains(p) || !shell.contains(p)) continue;
    b.points.push_back(p);
    if (fill) b.source.push_back(r.source[i]);
  }
  return b;
}

// Every q-th of the scan points skipped after each band point is taken back (q = stride: none),
// so that about refine_budget points are fitted.
std::size_t fill_step(const Band& b, std::size_t stride, const BoreOptions& o) {
  if (b.source.empty() || !o.refine_full_resolution || o.refine_budget <= b.points.size()) {
    return stride;
  }
  return std::max<std::size_t>(1, b.points.size() * stride / o.refine_budget + 1);
}

// The trimmed set: the band's points within `limit` of c and, where the region was read at a
// stride, every q-th of the scan points skipped after each of them (the rays next to a wall
// point mostly hit the wall too).
std::pmr::vector<Eigen::Vector3d> inliers(const RefineInput& in, const Band& b,
                                          const Heights& heights, const Cylinder& c, double limit,
                                          std::size_t q) {
  const Shell shell(c, std::max(c.radius - limit, 0.0), c.radius + limit);
  const std::size_t stride = in.region->stride;
  std::pmr::vector<Eigen::Vector3d> out(in.mr);
  out.reserve(b.points.size() * (stride / q + 1));
  for (std::size_t k = 0; k < b.points.size(); ++k) {
    if (shell.contains(b.points[k])) out.push_back(b.points[k]);
    if (q >= stride) continue;
    const std::size_t s = b.source[k];
    for (std::size_t j = s + q; j < s + stride && j < in.cloud.size(); j += q) {
      const Eigen::Vector3d& p = in.cloud[j];
      if (shell.contains(p) && heights.contains(p)) out.push_back(p);
    }
  }
  return out;
}

// A narrow arc (a large bore seen through a strip): the axis's offset across the arc trades
// against the radius, and on the budgeted points it stays several microns off (bore_benchmark's
// d50_60k: one-sigma 0.006 mm on ~8,000 points, the entrance's error all across the axis). Where
// the fit's own sigma says so, a trimmed step on every scan point of the band (~30,000 there:
// one-sigma 0.004 mm), and the sigma of those points. One step: a second one moves the
// entrance by about a micron more toward the full set's minimum and costs 0.13 ms.
void polish_full_resolution(const RefineInput& in, const Band& band, const Heights& heights,
                            double limit, CylinderLsfOptions lo, const BoreOptions& o,
                            RefineOutcome& out) {
  if (!(o.refine_polish_offset > 0.0) || o.refine_polish_steps <= 0 || !out.sigma.valid ||
      !(out.sigma.offset > o.refine_polish_offset)) {
    return;
  }
  const std::pmr::vector<Eigen::Vector3d> all =
      inliers(in, band, heights, out.lsf.cylinder, limit, 1);
  lo.max_iterations = o.refine_polish_steps;
  const CylinderLsfResult lsf = fit_cylinder_lsf(all, out.lsf.cylinder, lo);
  const CylinderSigma sigma = cylinder_sigma(all, lsf.cylinder, limit);
  if (!sigma.valid) return;
  const int before = out.lsf.iterations;
  out.lsf = lsf;
  out.lsf.iterations += before;
  out.inliers = all.size();
  out.sigma = sigma;
}

}  // namespace

// Geometric least squares on the band points, then again without those beyond 3 robust sigmas:
// ghosts just in front of the wall and outliers just behind it pass the normal test but bias a
// fit even under the Huber loss. Cost-bounded: the first fit iterates on a spread sample of the
// band (every k-th point in scan order) until a step moves the surface by less than 1e-3 mm,
// and the trimmed fit polishes it on the full-resolution inliers.
RefineOutcome refine_wall(const RefineInput& in, const Cylinder& start, const BoreOptions& o) {
  Heights heights{in.plane.point, in.up};
  Band band = collect_band(in, start, o, heights);
  CylinderLsfOptions lo = o.lsf;
  if (o.cost_bounded) lo.step_tolerance = 1e-4;
  std::pmr::vector<Eigen::Vector3d> sample(in.mr);
  std::span<const Eigen::Vector3d> first = band.points;
  if (o.cost_bounded && o.refine_sample > 0 && band.points.size() > o.refine_sample) {
    const std::size_t k = (band.points.size() + o.refine_sample - 1) / o.refine_sample;
    sample.reserve(band.points.size() / k + 1);
    for (std::size_t i = 0; i < band.points.size(); i += k) sample.push_back(band.points[i]);
    first = sample;
  }
  // The sample's own noise is ~noise / sqrt(n) ~ 1e-3 mm: iterating it further is wasted when
  // the full set's fit follows.
  CylinderLsfOptions first_lo = lo;
  if (!sample.empty()) first_lo.step_tolerance = 1e-3;
  RefineOutcome out;
  out.lsf = fit_cylinder_lsf(first, start, first_lo);
  out.inliers = first.size();
  if (first.size() <= 10) {
    if (!sample.empty()) {
      lo.max_iterations = std::min(lo.max_iterations, 1);
      out.lsf = fit_cylinder_lsf(band.points, out.lsf.cylinder, lo);
      out.inliers = band.points.size();
    }
    return out;
  }
  const double limit = trim_limit(first, out.lsf.cylinder, in.mr);
  const std::size_t q = fill_step(band, in.region->stride, o);
  const int done = out.lsf.iterations;
  std::pmr::vector<Eigen::Vector3d> kept(in.mr);
  const bool sampled = !sample.empty() && lo.method == LsfMethod::kLevenbergMarquardt;
  if (sampled && o.refine_full_resolution) {
    // A narrow arc (a large bore seen through a strip) leaves its radius and offset poorly
    // determined on the sample (0.1 mm off on a 50 mm bore), and a trim made once around the
    // sample's answer holds the fit there: Gauss-Newton steps that trim around every new
    // estimate, on the band's wide shell (with the skipped scan points taken back), one pass
    // over the points each.
    kept = inliers(in, band, heights, start, o.refine_band, q);
    lo.single_unchecked_step = true;
    lo.trim = limit;
    lo.max_iterations = std::min(lo.max_iterations, 4);
  } else {
    kept = inliers(in, band, heights, out.lsf.cylinder, limit, q);
    // The pipeline before: from the sample's minimum, one Gauss-Newton step on every inlier
    // (the one-step estimator).
    if (sampled) {
      lo.single_unchecked_step = true;
      lo.max_iterations = 1;
    }
  }
  out.lsf = fit_cylinder_lsf(kept, out.lsf.cylinder, lo);
  out.inliers = kept.size();
  if (out.lsf.iterations == 0) out.lsf.iterations = done;  // already at the minimum
  // How well these points determine the cylinder: the inliers within the trim of the answer.
  out.sigma = cylinder_sigma(kept, out.lsf.cylinder, limit);
  if (sampled && o.refine_full_resolution && q > 1) {
    polish_full_resolution(in, band, heights, limit, lo, o, out);
  }
  return out;
}

}  // namespace rangefit
