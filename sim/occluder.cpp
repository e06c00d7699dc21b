#include "sim/occluder.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

namespace rangefit::sim {
namespace {

constexpr int kBisections = 14;
constexpr int kOverhangTries = 4;
constexpr double kWallShortfall = 0.05;  // a wall that hides less than wanted - this: overhang

// A box (eps 0.1) with half sizes `half` along u, v = z x u and z, centred at `centre`.
ScenePart box(const std::string& name, const Eigen::Vector3d& half, const Eigen::Vector3d& u,
              const Eigen::Vector3d& centre) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = u;
  T.linear().col(1) = Eigen::Vector3d::UnitZ().cross(u);
  T.linear().col(2) = Eigen::Vector3d::UnitZ();
  T.translation() = centre;
  return {name, {half.x(), half.y(), half.z(), 0.1, 0.1, 0.0, 0.0}, T};
}

struct Fit {
  TableObject object;
  double share = 0.0;
};

// The occluder build(p), p in [0, 1], that hides `share`; build must hide more as p grows.
Fit bisect(const std::function<TableObject(double)>& build,
           const std::vector<SurfaceSample>& samples, const std::vector<bool>& already,
           double share) {
  const auto fit = [&](double p) {
    TableObject o = build(p);
    std::vector<bool> hidden = hidden_by(samples, PartCaster(o.parts));
    for (std::size_t i = 0; i < hidden.size(); ++i) hidden[i] = hidden[i] || already[i];
    return Fit{std::move(o), weighted_share(samples, hidden)};
  };
  Fit lo = fit(0.0), hi = fit(1.0);
  if (lo.share >= share) return lo;
  if (hi.share <= share) return hi;
  double a = 0.0, b = 1.0;
  for (int i = 0; i < kBisections && hi.share - lo.share > 0.005; ++i) {
    const double m = 0.5 * (a + b);
    Fit f = fit(m);
    if (f.share < share) {
      a = m, lo = std::move(f);
    } else {
      b = m, hi = std::move(f);
    }
  }
  return share - lo.share < hi.share - share ? lo : hi;
}

}  // namespace

Occluder make_occluder(const TableObject& target, const std::vector<SurfaceSample>& samples,
                       const std::vector<bool>& already, const StripeSweep& sweep, double share,
                       std::mt19937_64& rng) {
  const auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  const Eigen::AlignedBox3d bounds = object_bounds(target);
  const Eigen::Vector3d c(bounds.center().x(), bounds.center().y(), 0.0);
  const double top = bounds.max().z();
  // How far the target reaches from c along a horizontal direction.
  const auto extent = [&](const Eigen::Vector3d& u) { return reach(target, u) - u.dot(c); };
  // The target's middle across u and its width there.
  const auto across = [&](const Eigen::Vector3d& v, double& mid, double& width) {
    const double pos = extent(v), neg = extent(-v);
    mid = 0.5 * (pos - neg);
    width = pos + neg;
  };
  const double s_lo = std::min(sweep.position(0), sweep.position(sweep.profiles - 1));
  const double s_hi = std::max(sweep.position(0), sweep.position(sweep.profiles - 1));
  const ProfilePose pose = sweep.pose(std::clamp(sweep.position_of(bounds.center()), s_lo, s_hi));

  const double mode = uniform(0.0, 1.0);
  if (mode < 0.5) {
    // A wall beside the target, facing the camera (camera shadow) or the laser (laser shadow).
    const Eigen::Vector3d eye = mode < 0.35 ? pose.camera : pose.apex;
    Eigen::Vector3d u(eye.x() - c.x(), eye.y() - c.y(), 0.0);
    if (u.norm() < 1.0) u = Eigen::Vector3d::UnitX();
    u.normalize();
    const Eigen::Vector3d v = Eigen::Vector3d::UnitZ().cross(u);
    double mid, width;
    across(v, mid, width);
    width *= uniform(1.0, 1.6);
    const double offset = mid + uniform(-0.2, 0.2) * width;
    const double gap = uniform(2.0, 15.0), thick = uniform(8.0, 30.0);
    const double h_max = 0.6 * std::min(pose.apex.z(), pose.camera.z());
    const double along = extent(u) + gap + 0.5 * thick;
    const Fit wall = bisect(
        [&](double p) {
          const double h = 5.0 + p * (h_max - 5.0);
          const Eigen::Vector3d centre =
              c + along * u + offset * v + 0.5 * h * Eigen::Vector3d::UnitZ();
          return TableObject{
              "occluder/wall",
              {box("occluder/wall", {0.5 * thick, 0.5 * width, 0.5 * h}, u, centre)}};
        },
        samples, already, share);
    if (wall.share >= share - kWallShortfall) return {wall.object, "wall", wall.share};
  }
  // A plate above the target on a leg beside it, reaching across as far as needed.
  Occluder best;
  double best_error = INFINITY;
  for (int attempt = 0; attempt < kOverhangTries && best_error > 0.01; ++attempt) {
    const double phi = uniform(0.0, 2.0 * std::numbers::pi);
    const Eigen::Vector3d u(std::cos(phi), std::sin(phi), 0.0);
    const Eigen::Vector3d v = Eigen::Vector3d::UnitZ().cross(u);
    const double thick = uniform(8.0, 20.0), bottom = top + uniform(5.0, 30.0);
    const double leg_gap = uniform(5.0, 20.0), leg_thick = uniform(10.0, 25.0);
    double mid, width;
    across(v, mid, width);
    width += bottom;  // wide enough to shade the target from eyes off to the side
    const double leg_width = width * uniform(0.3, 1.0);
    const double outer = extent(u) + leg_gap + leg_thick, back = extent(-u);
    const ScenePart leg =
        box("occluder/leg", {0.5 * leg_thick, 0.5 * leg_width, 0.5 * bottom}, u,
            c + (outer - 0.5 * leg_thick) * u + mid * v + 0.5 * bottom * Eigen::Vector3d::UnitZ());
    const Fit f = bisect(
        [&](double p) {
          const double inner = outer - 5.0 - p * (outer - 5.0 + back + bottom);
          const Eigen::Vector3d centre = c + 0.5 * (inner + outer) * u + mid * v +
                                         (bottom + 0.5 * thick) * Eigen::Vector3d::UnitZ();
          return TableObject{
              "occluder/overhang",
              {leg, box("occluder/plate", {0.5 * (outer - inner), 0.5 * width, 0.5 * thick}, u,
                        centre)}};
        },
        samples, already, share);
    if (std::abs(f.share - share) < best_error) {
      best_error = std::abs(f.share - share);
      best = {f.object, "overhang", f.share};
    }
  }
  return best;
}

}  // namespace rangefit::sim
