#include "sim/visible_surface.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rangefit::sim {
namespace {

constexpr double kMaxFanHalf = 85.0 * std::numbers::pi / 180.0;  // "any" fan angle

void sample_part(const PartCaster& caster, int part, const StripeSweep& sweep, bool within_scan,
                 double spacing_ratio, std::vector<SurfaceSample>& out) {
  const Eigen::Vector3d c = caster.sphere_centre(part);
  // Thin parts (the mallet's shaft) get at least four rays across.
  const double R = caster.sphere_radius(part);
  const double spacing = std::min(
      spacing_ratio * R, 0.25 * caster.parts()[static_cast<std::size_t>(part)].model.min_size());
  const double s_c = sweep.position_of(c);
  if (std::isnan(s_c)) return;
  // Sweep positions across the sphere, about `spacing` apart at the part.
  double half, ds;
  if (sweep.kind == SensorView::Kind::kRotarySweep) {
    const Eigen::Vector3d q = c - sweep.pivot;
    const double r_axis = (q - q.dot(sweep.direction) * sweep.direction).norm();
    if (r_axis <= R) return;  // the turn axis runs through the part: not a scene of ours
    half = std::asin(R / r_axis);
    ds = spacing / r_axis;
  } else {
    const double nd = std::abs(sweep.pose(0.0).normal.dot(sweep.direction));
    half = R / nd;
    ds = spacing / nd;
  }
  const double lo = std::min(sweep.position(0), sweep.position(sweep.profiles - 1));
  const double hi = std::max(sweep.position(0), sweep.position(sweep.profiles - 1));
  const double fan_half = within_scan ? 0.5 * sweep.fan_rad : kMaxFanHalf;
  const int steps = static_cast<int>(std::ceil(half / ds));
  for (int i = -steps; i <= steps; ++i) {
    const double s = s_c + i * ds;
    if (within_scan && (s < lo || s > hi)) continue;
    const ProfilePose pose = sweep.pose(s);
    const Eigen::Vector3d v0 = c - pose.apex;
    const double delta = pose.normal.dot(v0);
    if (std::abs(delta) >= R) continue;
    const Eigen::Vector3d v = v0 - delta * pose.normal;
    const double rho = std::sqrt(R * R - delta * delta), dist = v.norm();
    if (dist <= rho) continue;  // an eye inside the bounds: not a scene of ours
    const double mid = std::atan2(pose.line.dot(v), pose.centre.dot(v));
    const double span = std::asin(rho / dist), da = spacing / dist;
    const int rays = static_cast<int>(std::ceil(span / da));
    for (int k = -rays; k <= rays; ++k) {
      const double a = mid + k * da;
      if (std::abs(a) > fan_half) continue;
      const auto m = measure_ray(caster, pose, pose.ray(a));
      if (!m || m->label != part) continue;
      out.push_back({m->point, pose.apex, m->seen_by, ds * da});
    }
  }
}

}  // namespace

std::vector<SurfaceSample> visible_samples(const PartCaster& caster, const std::vector<int>& parts,
                                           const StripeSweep& sweep, bool within_scan,
                                           double spacing_ratio) {
  std::vector<SurfaceSample> out;
  if (sweep.profiles <= 0) return out;
  for (int p : parts) sample_part(caster, p, sweep, within_scan, spacing_ratio, out);
  return out;
}

std::vector<bool> hidden_by(const std::vector<SurfaceSample>& samples, const PartCaster& others) {
  std::vector<bool> hidden(samples.size(), false);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const SurfaceSample& s = samples[i];
    bool camera_blocked = true;
    for (int k = 0; k < s.cameras.count && camera_blocked; ++k) {
      camera_blocked = others.blocked(s.point, s.cameras.camera[static_cast<std::size_t>(k)]);
    }
    hidden[i] = others.blocked(s.apex, s.point) || camera_blocked;
  }
  return hidden;
}

double total_weight(const std::vector<SurfaceSample>& samples) {
  double w = 0.0;
  for (const SurfaceSample& s : samples) w += s.weight;
  return w;
}

double weighted_share(const std::vector<SurfaceSample>& samples, const std::vector<bool>& mask) {
  double w = 0.0, all = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    all += samples[i].weight;
    if (mask[i]) w += samples[i].weight;
  }
  return all > 0.0 ? w / all : 0.0;
}

}  // namespace rangefit::sim
