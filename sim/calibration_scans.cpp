#include "sim/calibration_scans.hpp"

#include <cmath>
#include <random>

#include "sim/ranger_simulator.hpp"
#include "sim/ray_caster.hpp"

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;

// Noise along the fan ray and the chip's rounding, as the simulated ranger device applies them.
hal::RangerProfile to_profile(const ProfileTruth& truth, const hal::StripeRanger& r,
                              const RangerNoise& noise, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const int n = r.points_per_profile;
  hal::RangerProfile p;
  p.x_mm.assign(static_cast<std::size_t>(n), hal::kNoReturn);
  p.z_mm.assign(static_cast<std::size_t>(n), hal::kNoReturn);
  for (int k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (std::isnan(truth.z_mm[i])) continue;
    const Vector3d dir = r.ray_direction(k, n);
    double range = std::hypot(truth.x_mm[i], truth.z_mm[i]);
    if (noise.sigma_mm > 0.0) range += noise.sigma_mm * gauss(rng);
    double x = range * dir.x(), z = range * dir.z();
    if (noise.quantise) quantise_to_chip(r, k, x, z);
    if (!r.depth_in_range(z)) continue;
    p.x_mm[i] = static_cast<float>(x);
    p.z_mm[i] = static_cast<float>(z);
  }
  return p;
}

}  // namespace

Scene calibration_cube_scene(double edge_mm, double bar_mm, const Eigen::Isometry3d& T_scene_cube,
                             bool table) {
  Scene scene;
  scene.source = "calibration cube";
  const double h = 0.5 * edge_mm, c = h - 0.5 * bar_mm;
  // Bar along axis a at the two other coordinates +-c: twelve bars, overlapping at the corners.
  for (int a = 0; a < 3; ++a) {
    for (int s1 = -1; s1 <= 1; s1 += 2) {
      for (int s2 = -1; s2 <= 1; s2 += 2) {
        Vector3d size = Vector3d::Constant(bar_mm);
        size[a] = edge_mm;
        Vector3d centre = Vector3d::Zero();
        centre[(a + 1) % 3] = s1 * c;
        centre[(a + 2) % 3] = s2 * c;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = centre;
        scene.objects.push_back(
            {"cube_bar_" + std::to_string(scene.objects.size()), BoxShape{size}, T_scene_cube * T});
      }
    }
  }
  if (table)
    scene.objects.push_back({"table", PlaneShape{2000.0, 2000.0}, Eigen::Isometry3d::Identity()});
  return scene;
}

std::vector<hal::RangerProfile> simulate_stripe_sweep(const Scene& scene,
                                                      const hal::StripeCellGeometry& cell,
                                                      const std::vector<double>& axis_mm,
                                                      const RangerNoise& noise) {
  const RayCaster caster(scene);
  std::mt19937_64 rng(noise.seed);
  std::vector<hal::RangerProfile> out;
  out.reserve(axis_mm.size());
  for (const double s : axis_mm) {
    out.push_back(to_profile(cast_profile(caster, cell.ranger, cell.T_world_ranger(s)), cell.ranger,
                             noise, rng));
  }
  return out;
}

std::vector<hal::RangerProfile> simulate_pan_tilt_sweep(
    const Scene& scene, const hal::PanTiltGeometry& head,
    const std::vector<hal::PanTiltSample>& angles, const RangerNoise& noise) {
  const RayCaster caster(scene);
  std::mt19937_64 rng(noise.seed);
  std::vector<hal::RangerProfile> out;
  out.reserve(angles.size());
  for (const hal::PanTiltSample& a : angles) {
    out.push_back(
        to_profile(cast_profile(caster, head.ranger, head.T_world_ranger(a.pan_rad, a.tilt_rad)),
                   head.ranger, noise, rng));
  }
  return out;
}

std::vector<CssRangeSample> simulate_css_sphere_scan(
    const hal::CssGeometry& sensor, const Eigen::Isometry3d& T_joint_css, double omega_zero_rad,
    const Eigen::Isometry3d& T_base_joint, const std::vector<double>& omega,
    const Vector3d& centre_base_mm, double radius_mm, double sigma_mm, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<CssRangeSample> out;
  const int n = hal::CssRevolution::kSamples;
  for (const double w : omega) {
    const Eigen::Isometry3d T_base_css =
        T_base_joint * Eigen::AngleAxisd(w - omega_zero_rad, Vector3d::UnitY()) * T_joint_css;
    const Vector3d origin = T_base_css * sensor.laser_point();
    const Vector3d ccd = T_base_css * sensor.ccd_point();
    for (int i = 0; i < n; ++i) {
      const double beam = sensor.beam_angle(i, n);
      const Vector3d dir = T_base_css.linear() * sensor.beam_direction(beam);
      // Ray-sphere: |o + t d - c|^2 = r^2, the near root.
      const Vector3d oc = origin - centre_base_mm;
      const double b = oc.dot(dir), disc = b * b - (oc.squaredNorm() - radius_mm * radius_mm);
      if (disc < 0.0) continue;
      const double t = -b - std::sqrt(disc);
      if (t < sensor.min_range_mm || t > sensor.max_range_mm) continue;
      // The CCD sees the spot only from the lit side of the sphere.
      const Vector3d hit = origin + t * dir;
      if ((ccd - hit).dot(hit - centre_base_mm) <= 0.0) continue;
      out.push_back({w, beam, t + sigma_mm * gauss(rng)});
    }
  }
  return out;
}

}  // namespace rangefit::sim
