#include "sim/stripe_scan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "detect/common/parallel_for.hpp"

namespace rangefit::sim {
namespace {

constexpr double kSegmentEndMm = 1e-3;  // segment ends left out of the shadow test
constexpr double kMinFacing = 1e-6;     // cosine: surfaces edge-on to the camera are not seen

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// Radius about c of a sphere holding the part: the farthest of its surface points on a grid of
// latitudes and longitudes (eq. 2.14, every pi/16, so the extremes of the symmetric shapes are
// on it) plus 2 %, at most the bounds' half diagonal (which box-like parts come close to).
double bounding_radius(const Superquadric& sq, const Eigen::Vector3d& c) {
  const double box = 0.5 * part_bounds(sq).sizes().norm() + 1e-6;
  if (sq.eps1 <= 0.25 && sq.eps2 <= 0.25 && sq.kx == 0.0 && sq.ky == 0.0) return box;  // a box
  constexpr int kN = 32;
  double r = 0.0;
  for (int i = 0; i <= kN / 2; ++i) {
    for (int j = 0; j < kN; ++j) {
      const double eta = -0.5 * std::numbers::pi + std::numbers::pi * i / (kN / 2);
      const double omega = -std::numbers::pi + 2.0 * std::numbers::pi * j / kN;
      r = std::max(r, (surface_point(sq, eta, omega) - c).norm());
    }
  }
  return std::min(1.02 * r + 1e-3, box);
}

struct Row {
  std::vector<int> column;
  std::vector<Eigen::Vector3d> point;
  std::vector<std::int32_t> label;
};

// Fan rays k_lo..k_hi of the profile can meet part `part`'s bounding sphere.
struct Candidate {
  int part, k_lo, k_hi;
};

std::vector<Candidate> candidates(const PartCaster& caster, const StripeSweep& sweep,
                                  const ProfilePose& pose) {
  std::vector<Candidate> out;
  const double n1 = sweep.rays - 1;
  for (int i = 0; i < static_cast<int>(caster.parts().size()); ++i) {
    const double r = caster.sphere_radius(i);
    const Eigen::Vector3d v0 = caster.sphere_centre(i) - pose.apex;
    const double delta = pose.normal.dot(v0);
    if (std::abs(delta) >= r) continue;  // the sphere misses the laser plane
    const double rho = std::sqrt(r * r - delta * delta);
    const Eigen::Vector3d v = v0 - delta * pose.normal;
    const double dist = v.norm();
    int lo = 0, hi = sweep.rays - 1;
    if (dist > rho) {
      const double mid = std::atan2(pose.line.dot(v), pose.centre.dot(v));
      const double half = std::asin(rho / dist);
      const auto k_of = [&](double a) { return (a + 0.5 * sweep.fan_rad) / sweep.fan_rad * n1; };
      const double a = std::floor(k_of(mid - half)), b = std::ceil(k_of(mid + half));
      if (b < 0.0 || a > n1) continue;
      lo = static_cast<int>(std::max(0.0, a));
      hi = static_cast<int>(std::min(n1, b));
    }
    out.push_back({i, lo, hi});
  }
  return out;
}

Row scan_profile(const PartCaster& caster, const StripeSweep& sweep, const ScanNoise& noise,
                 int j) {
  Row row;
  const ProfilePose pose = sweep.pose(sweep.position(j));
  const std::vector<Candidate> near = candidates(caster, sweep, pose);
  std::vector<int> list;
  std::mt19937_64 rng(splitmix64(noise.seed ^ splitmix64(static_cast<std::uint64_t>(j) + 1)));
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int k = 0; k < sweep.rays; ++k) {
    list.clear();
    for (const Candidate& c : near) {
      if (k >= c.k_lo && k <= c.k_hi) list.push_back(c.part);
    }
    const Eigen::Vector3d dir = pose.ray(sweep.ray_angle(k));
    const auto m = measure_ray(caster, pose, dir, 1e5, &list);
    if (!m) continue;
    double range = m->range_mm + noise.sigma_mm * gauss(rng);
    std::int32_t label = m->label;
    if (uniform(rng) < noise.outlier_share) {
      range = m->range_mm * (0.6 + 0.45 * uniform(rng));
      label = kOutlierLabel;
    }
    row.column.push_back(k);
    row.point.push_back(pose.apex + range * dir);
    row.label.push_back(label);
  }
  return row;
}

}  // namespace

PartCaster::PartCaster(std::vector<ScenePart> parts, Eigen::AlignedBox2d table)
    : parts_(std::move(parts)), table_(table) {
  for (const ScenePart& p : parts_) {
    const Eigen::AlignedBox3d box = part_bounds(p.model);
    centres_.push_back(p.T_world_part * box.center());
    radii_.push_back(bounding_radius(p.model, box.center()));
  }
}

std::optional<PartCaster::Hit> PartCaster::first_hit(const Eigen::Vector3d& o,
                                                     const Eigen::Vector3d& dir, double t_max,
                                                     const std::vector<int>* candidates) const {
  std::optional<Hit> best;
  double t_best = t_max;
  if (dir.z() < 0.0) {
    const double t = -o.z() / dir.z();
    const Eigen::Vector3d p = o + t * dir;
    if (t > 0.0 && t <= t_best && table_.contains(Eigen::Vector2d(p.x(), p.y()))) {
      best = Hit{kTableLabel, t};
      t_best = t;
    }
  }
  const auto try_part = [&](int i) {
    const Eigen::Vector3d v = centres_[i] - o;
    const double tc = v.dot(dir), r = radii_[i];
    if (tc + r < 0.0 || tc - r > t_best || v.squaredNorm() - tc * tc > r * r) return;
    const ScenePart& p = parts_[i];
    const auto t = intersect_superquadric(p.model, p.T_world_part, o, dir, t_best);
    if (t && *t < t_best) {
      best = Hit{i, *t};
      t_best = *t;
    }
  };
  if (candidates) {
    for (int i : *candidates) try_part(i);
  } else {
    for (int i = 0; i < static_cast<int>(parts_.size()); ++i) try_part(i);
  }
  return best;
}

bool PartCaster::blocked(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int skip) const {
  const Eigen::Vector3d d = b - a;
  const double len2 = d.squaredNorm(), len = std::sqrt(len2);
  if (len <= 2.0 * kSegmentEndMm) return false;
  const double eps = kSegmentEndMm / len;
  for (int i = 0; i < static_cast<int>(parts_.size()); ++i) {
    if (i == skip) continue;
    const double u = std::clamp((centres_[i] - a).dot(d) / len2, 0.0, 1.0);
    if ((a + u * d - centres_[i]).squaredNorm() > radii_[i] * radii_[i]) continue;
    const ScenePart& p = parts_[i];
    if (intersect_superquadric(p.model, p.T_world_part, a, d, 1.0 - eps, eps)) return true;
  }
  return false;
}

Eigen::Vector3d PartCaster::normal(std::int32_t label, const Eigen::Vector3d& p) const {
  if (label < 0) return Eigen::Vector3d::UnitZ();
  const ScenePart& part = parts_[static_cast<std::size_t>(label)];
  return superquadric_normal(part.model, part.T_world_part, p);
}

std::optional<Measurement> measure_ray(const PartCaster& caster, const ProfilePose& pose,
                                       const Eigen::Vector3d& dir, double max_range_mm,
                                       const std::vector<int>* candidates) {
  const auto hit = caster.first_hit(pose.apex, dir, max_range_mm, candidates);
  if (!hit) return std::nullopt;
  const Eigen::Vector3d p = pose.apex + hit->t * dir;
  const SeenBy seen = cameras_seeing(caster, pose, p, hit->label);
  if (seen.count == 0) return std::nullopt;
  return Measurement{hit->label, hit->t, p, seen};
}

SeenBy cameras_seeing(const PartCaster& caster, const ProfilePose& pose, const Eigen::Vector3d& p,
                      std::int32_t label) {
  SeenBy seen;
  const Eigen::Vector3d n = caster.normal(label, p);
  for (const std::optional<Eigen::Vector3d>& camera :
       {std::optional<Eigen::Vector3d>(pose.camera), pose.second_camera}) {
    if (!camera) continue;
    const Eigen::Vector3d to_camera = *camera - p;
    // The surface's back or its edge; a convex part cannot hide its own front face, so only the
    // others are tested for the camera's shadow.
    if (n.dot(to_camera) <= kMinFacing * to_camera.norm()) continue;
    if (caster.blocked(p, *camera, label)) continue;
    seen.camera[static_cast<std::size_t>(seen.count++)] = *camera;
  }
  return seen;
}

StripeScan scan_stripe(const PartCaster& caster, const StripeSweep& sweep, const ScanNoise& noise,
                       int threads) {
  StripeScan out;
  if (sweep.profiles <= 0 || sweep.rays < 2) return out;
  std::vector<Row> rows(static_cast<std::size_t>(sweep.profiles));
  parallel_for(rows.size(), threads, [&](std::size_t j) {
    rows[j] = scan_profile(caster, sweep, noise, static_cast<int>(j));
  });

  std::size_t total = 0;
  for (const Row& r : rows) total += r.point.size();
  out.cloud.points.reserve(total);
  out.label.reserve(total);
  out.profile.reserve(total);
  GridLayout& grid = out.cloud.grid;
  grid.rows = sweep.profiles;
  grid.cols = sweep.rays;
  grid.index.assign(static_cast<std::size_t>(grid.rows) * grid.cols, -1);
  for (int j = 0; j < sweep.profiles; ++j) {
    const Row& r = rows[static_cast<std::size_t>(j)];
    for (std::size_t i = 0; i < r.point.size(); ++i) {
      grid.index[static_cast<std::size_t>(j) * grid.cols + r.column[i]] =
          static_cast<std::int32_t>(out.cloud.points.size());
      out.cloud.points.push_back(r.point[i]);
      out.label.push_back(r.label[i]);
      out.profile.push_back(j);
    }
  }
  return out;
}

}  // namespace rangefit::sim
