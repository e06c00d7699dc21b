// 4.1.1 the CAD prior as a frame, and the region of interest around its entrance.
#include <algorithm>
#include <cmath>

#include "detect/bore/bore_stages.hpp"

namespace rangefit::bore {
namespace {

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// The radius whose wall eq. 4.6 can find: a countersink's cylinder, an ellipse's larger
// semi-axis (the band then holds both), else the CAD radius.
double segmented_radius(const BorePrior& prior) {
  if (prior.half_angle > 0.0 && prior.cylinder_radius > 0.0) return prior.cylinder_radius;
  return std::max(prior.radius, prior.radius2);
}

std::pmr::vector<WallTarget> wall_targets(const BorePrior& prior, const BoreOptions& o,
                                          std::pmr::memory_resource* mr) {
  const double r_in = segmented_radius(prior);
  const double r_out = prior.outer_radius > r_in ? prior.outer_radius : 0.0;
  const double mid = 0.5 * (r_in + r_out);
  std::pmr::vector<WallTarget> t(mr);
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

}  // namespace

double StageClock::lap() {
  const Clock::time_point t = Clock::now();
  const double ms = std::chrono::duration<double, std::milli>(t - last_).count();
  last_ = t;
  return ms;
}

double StageClock::total() const {
  return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
}

bool valid_input(const BorePrior& prior, const BoreOptions& o) {
  const Eigen::Vector3d plane_prior = prior.plane_normal.value_or(prior.axis);
  return finite(prior.entrance) && finite(prior.axis) && finite(plane_prior) &&
         std::isfinite(prior.radius) && prior.radius > 0.0 && prior.axis.norm() > 1e-9 &&
         plane_prior.norm() > 1e-9 && o.normal_radius > 0.0 && o.roi_radius_factor > 0.0 &&
         std::isfinite(prior.outer_radius) &&
         !(o.walls == BoreWalls::kBoth && !(prior.outer_radius > prior.radius)) &&
         !(o.view_dir && !(finite(*o.view_dir) && o.view_dir->norm() > 1e-9)) &&
         !(o.sensor_position && !finite(*o.sensor_position));
}

BoreFrame bore_frame(const BorePrior& prior, const BoreOptions& o, std::pmr::memory_resource* mr) {
  BoreFrame f(mr);
  f.entrance = prior.entrance;
  const Eigen::Vector3d plane_prior = prior.plane_normal.value_or(prior.axis);
  // Orientation convention: everything toward the sensor (view direction, else plane normal).
  f.view = o.view_dir ? o.view_dir->normalized() : plane_prior.normalized();
  f.n_cad = plane_prior.normalized();
  if (f.n_cad.dot(f.view) < 0.0) f.n_cad = -f.n_cad;
  f.a_cad = prior.axis.normalized();
  if (f.a_cad.dot(f.view) < 0.0) f.a_cad = -f.a_cad;
  f.targets = wall_targets(prior, o, mr);
  f.r_min = f.r_max = f.targets.front().radius;
  for (const auto& w : f.targets) {
    f.r_min = std::min(f.r_min, w.radius);
    f.r_max = std::max(f.r_max, w.radius);
  }
  f.r_max = std::max(f.r_max, prior.radius);  // a countersink's entrance radius sets the region
  // Beyond the thesis: a patch as large as a small bore's radius is too curved for eq. 4.4.
  f.normal_radius = std::min(o.normal_radius, o.normal_radius_max_share * f.r_min);
  // A pipe's end face is only as wide as its wall: a larger patch straddles an edge everywhere
  // and eq. 4.4 would leave no plane (thesis fig. 4.33).
  if (prior.outer_radius > prior.radius) {
    f.normal_radius = std::min(f.normal_radius, 0.25 * (prior.outer_radius - prior.radius));
  }
  f.roi_radius = o.roi_radius_factor * f.r_max;
  return f;
}

// The region and the normal neighbourhood pool around it. Cost-bounded: read within the region
// budget, and split into the points near an expected wall and the rest (by their distance from
// the CAD axis and their depth below the CAD plane), each thinned to its own normal budget.
BoreRegion region_of_interest(const PointCloud& cloud, const BoreFrame& f, const BoreOptions& o,
                              std::pmr::memory_resource* mr) {
  RegionShape shape;
  shape.centre = f.entrance;
  shape.axis = f.a_cad;
  shape.plane_normal = f.n_cad;
  shape.roi_radius = f.roi_radius;
  shape.pool_radius = f.roi_radius + f.normal_radius;
  shape.rho_lo = 1e300;
  for (const auto& w : f.targets) {
    shape.rho_lo = std::min(shape.rho_lo, w.rho_lo);
    shape.rho_hi = std::max(shape.rho_hi, w.rho_hi);
  }
  // Below the CAD plane by more than the prior's offset can explain: not the entrance plane.
  shape.below_margin = std::max(0.1 * f.r_min, 0.5);
  shape.split = o.cost_bounded;
  return select_region(cloud.points, shape, o.cost_bounded ? o.region_budget : 0, mr);
}

}  // namespace rangefit::bore
