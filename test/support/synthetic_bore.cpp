#include "test/support/synthetic_bore.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "detect/common/angles.hpp"

namespace rangefit::sim {
namespace {

// The part in its own frame: top surface z = height(x, y) through the origin, bore entrance at
// the origin, axis a (out of the bore) tilted by the slant about the part's y axis.
class Part {
 public:
  explicit Part(const SyntheticBoreOptions& o) : o_(o) {
    r_ = o.radius;
    depth_ = o.depth > 0.0 ? o.depth : 6.0 * r_;
    axis_ = Eigen::Vector3d(std::sin(o.slant_deg * kDeg), 0.0, std::cos(o.slant_deg * kDeg));
    // Azimuth reference: e1_ lies in the plane of the axis and the part's x axis.
    e1_ = Eigen::Vector3d::UnitY().cross(axis_).normalized();
    e2_ = axis_.cross(e1_);
    const double az = o.neighbour_azimuth_deg * kDeg;
    neighbour_ = (2.0 * r_ + o.neighbour_gap) * (std::cos(az) * e1_ + std::sin(az) * e2_);
  }

  const Eigen::Vector3d& axis() const { return axis_; }
  const Eigen::Vector3d& e1() const { return e1_; }
  const Eigen::Vector3d& e2() const { return e2_; }

  double height(double x, double y) const {
    switch (o_.surface) {
      case TopSurface::kCurved:
        return -x * x / (2.0 * o_.curvature_radius);
      case TopSurface::kBumpy: {
        const double k = 2.0 * std::numbers::pi / o_.bump_wavelength;
        return o_.bump_amplitude * std::sin(k * x) * std::sin(k * y);
      }
      case TopSurface::kPlane:
        break;
    }
    return 0.0;
  }

  bool pipe() const { return o_.outer_radius > r_; }
  double depth() const { return depth_; }

  // True where the ray travels through air: above the surface or inside a bore (or, for a
  // pipe, anywhere but between its two walls).
  bool air(const Eigen::Vector3d& p) const {
    const double below = height(p.x(), p.y()) - p.z();
    if (below < 0.0) return true;
    if (pipe()) {
      const double h = p.dot(axis_);
      const double rho2 = (p - h * axis_).squaredNorm();
      return -h > depth_ || rho2 < r_ * r_ || rho2 > o_.outer_radius * o_.outer_radius;
    }
    if (in_bore(p, Eigen::Vector3d::Zero(), below, true)) return true;
    return o_.neighbour && in_bore(p, neighbour_, below, false);
  }

 private:
  bool in_bore(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, double below,
               bool main) const {
    const Eigen::Vector3d d = p - centre;
    const double h = d.dot(axis_);
    if (-h > depth_) return false;  // the blind bore's bottom
    const Eigen::Vector3d radial = d - h * axis_;
    double rho = main ? wall_radius(radial, -h) : r_;
    const double e = o_.edge_size;
    if (o_.edge == BoreEdge::kChamfer && below < e) rho += e - below;
    if (o_.edge == BoreEdge::kRounded && below < e) {
      rho += e - std::sqrt(std::max(0.0, e * e - (e - below) * (e - below)));
    }
    if (main && o_.notches > 0 && -h > 0.5 && -h < 0.6 * depth_) {
      // Grooves spread over the side facing away from +e1 (the visible wall).
      const double phi = std::atan2(radial.dot(e2_), radial.dot(e1_));
      for (int k = 0; k < o_.notches; ++k) {
        const double centre_phi = std::numbers::pi + (k - 0.5 * (o_.notches - 1)) * 40.0 * kDeg;
        const double diff = std::remainder(phi - centre_phi, 2.0 * std::numbers::pi);
        if (std::abs(diff) < 0.5 * o_.notch_width_deg * kDeg) rho += o_.notch_depth;
      }
    }
    return radial.squaredNorm() < rho * rho;
  }

  // The main bore's radius at this depth and direction: a cone down into the bore, an ellipse.
  double wall_radius(const Eigen::Vector3d& radial, double depth) const {
    if (o_.cone_radius > r_) {
      return std::max(r_, o_.cone_radius - depth * std::tan(o_.cone_half_angle_deg * kDeg));
    }
    if (o_.radius2 > 0.0) {
      const double psi = std::atan2(radial.dot(e2_), radial.dot(e1_)) - o_.major_azimuth_deg * kDeg;
      return r_ * o_.radius2 / std::hypot(o_.radius2 * std::cos(psi), r_ * std::sin(psi));
    }
    return r_;
  }

  const SyntheticBoreOptions& o_;
  double r_ = 0.0, depth_ = 0.0;
  Eigen::Vector3d axis_, e1_, e2_, neighbour_;
};

// First solid point along origin - t * dir, or false when the ray leaves the scene.
bool cast(const Part& part, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_max,
          double step, Eigen::Vector3d& hit) {
  // Surface crossing by fixed-point iteration (gentle slopes converge in a few steps).
  double t = origin.z() / dir.z();
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d p = origin - t * dir;
    t = (origin.z() - part.height(p.x(), p.y())) / dir.z();
  }
  if (!part.air(origin - (t + 1e-9) * dir)) {
    hit = origin - t * dir;
    return true;
  }
  // Inside a bore opening: march, then bisect the air/solid transition.
  double lo = t;
  for (double hi = t + step; hi < t_max; lo = hi, hi += step) {
    if (part.pipe() && (origin - hi * dir).z() < -(part.depth() + 1.0)) return false;
    if (part.air(origin - hi * dir)) continue;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      (part.air(origin - mid * dir) ? lo : hi) = mid;
    }
    hit = origin - hi * dir;
    return true;
  }
  return false;
}

}  // namespace

SyntheticBoreScan make_synthetic_bore(const SyntheticBoreOptions& o) {
  SyntheticBoreScan scan;
  if (!(o.radius > 0.0) || !(o.view_tilt_deg >= 0.0 && o.view_tilt_deg < 80.0)) return scan;
  const Part part(o);
  const double r = o.radius;
  const double extent = o.extent > 0.0 ? o.extent : 2.6 * r;
  const double spacing = o.spacing > 0.0 ? o.spacing : std::clamp(r / 25.0, 0.1, 0.4);

  // View direction: the axis tilted toward +e1, so the wall around -e1 faces the sensor.
  const double tilt = o.view_tilt_deg * kDeg;
  const Eigen::Vector3d view = std::cos(tilt) * part.axis() + std::sin(tilt) * part.e1();
  const Eigen::Vector3d w1 = view.cross(part.e2()).normalized();
  const Eigen::Vector3d w2 = view.cross(w1);
  const double extent_v = o.extent_v > 0.0 ? o.extent_v : extent;
  const double lift = 2.0 * std::max(extent, extent_v);  // rays start well above the part
  const int n = static_cast<int>(std::floor(2.0 * extent / spacing)) + 1;
  const int nv = static_cast<int>(std::floor(2.0 * extent_v / spacing)) + 1;
  const int passes = std::max(1, o.passes);
  const double t_max = lift + 6.0 * r + 8.0 * std::max(extent, extent_v);

  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, o.noise_sigma);

  PointCloud& cloud = scan.cloud;
  cloud.frame_id = "world";
  if (o.organised) {
    cloud.grid.rows = passes * n;
    cloud.grid.cols = nv;
    cloud.grid.index.assign(static_cast<std::size_t>(passes) * n * nv, -1);
  }
  for (int pass = 0; pass < passes; ++pass) {
    // Later passes: the grid turned about the view and shifted by a fraction of a ray spacing,
    // so their rays fall between the first pass's, as the CSS's overlapping scan circles do.
    const double turn = 7.0 * kDeg * pass;
    const Eigen::Vector3d u1 = std::cos(turn) * w1 + std::sin(turn) * w2;
    const Eigen::Vector3d u2 = std::cos(turn) * w2 - std::sin(turn) * w1;
    const double shift = pass == 0 ? 0.0 : 0.37 * spacing;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < nv; ++j) {
        const Eigen::Vector3d origin = (i * spacing - extent + shift) * u1 +
                                       (j * spacing - extent_v + 1.6 * shift) * u2 + lift * view;
        Eigen::Vector3d p;
        if (!cast(part, origin, view, t_max, o.march_step, p)) continue;
        // Only the square around the bore counts as scanned (rays are tilted against the part).
        const double roll = uni(rng);
        if (roll < o.ghost_fraction) {
          p += (0.5 + 4.5 * uni(rng)) * view;  // reflection ghost in front of the surface
        } else if (roll < o.ghost_fraction + o.outlier_fraction) {
          p += (2.0 * uni(rng) - 1.0) * o.outlier_amplitude * view;
        } else {
          p += noise(rng) * view;
        }
        if (o.organised) {
          cloud.grid.index[(static_cast<std::size_t>(pass) * n + i) * nv + j] =
              static_cast<std::int32_t>(cloud.points.size());
        }
        cloud.points.push_back(o.T_world_part * p);
      }
    }
  }

  // Ground truth entrance: the axis meets the mean height of the surface over the annulus a
  // plane fit sees (r..2r), which is the thesis's definition (axis cap fitted plane).
  double mean_h = 0.0;
  int count = 0;
  for (double rho = 1.1 * r; rho < 2.0 * r; rho += 0.05 * r) {
    for (int k = 0; k < 72; ++k, ++count) {
      mean_h += part.height(rho * std::cos(k * 5.0 * kDeg), rho * std::sin(k * 5.0 * kDeg));
    }
  }
  mean_h /= count;
  const Eigen::Vector3d entrance = part.axis() * (mean_h / part.axis().z());
  scan.truth.entrance = o.T_world_part * entrance;
  scan.truth.axis = o.T_world_part.linear() * part.axis();
  scan.truth.radius = r;
  scan.truth.outer_radius = part.pipe() ? o.outer_radius : 0.0;
  if (o.cone_radius > r) {
    scan.truth.cone_radius = o.cone_radius;
    scan.truth.half_angle = o.cone_half_angle_deg * kDeg;
  }
  scan.truth.radius2 = o.radius2 > 0.0 ? o.radius2 : 0.0;
  const double az = o.major_azimuth_deg * kDeg;
  scan.truth.major_axis =
      o.T_world_part.linear() * (std::cos(az) * part.e1() + std::sin(az) * part.e2());
  scan.truth.plane_normal = o.T_world_part.linear() * Eigen::Vector3d::UnitZ();
  scan.truth.view_dir = o.T_world_part.linear() * view;
  return scan;
}

}  // namespace rangefit::sim
