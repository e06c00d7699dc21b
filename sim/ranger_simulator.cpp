#include "sim/ranger_simulator.hpp"

#include <cmath>
#include <limits>

#include "sim/simulated_stream.hpp"

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;

class RangerDevice final : public SimulatedStream<hal::RangerProfile> {
 public:
  RangerDevice(std::string name, const RayCaster& caster, RangerOptions options, RangerPoseFn pose,
               hal::Clock& clock, hal::Timestamp start)
      : SimulatedStream(std::move(name), clock, options.faults, options.seed, 3),
        caster_(caster),
        options_(std::move(options)),
        pose_(std::move(pose)),
        start_(start) {}

 protected:
  hal::Timestamp due(std::uint64_t k) const override {
    return exposure_centre(k) + options_.exposure / 2 + std::chrono::milliseconds(1);
  }

  void make(std::uint64_t k, std::mt19937_64& rng, hal::RangerProfile& p) override {
    const FaultOptions& f = faults();
    const hal::StripeRanger& r = options_.ranger;
    const hal::Timestamp t = exposure_centre(k);
    const ProfileTruth truth = cast_profile(caster_, r, pose_(t));
    p.sequence = static_cast<std::uint32_t>(k);
    p.stamp = stamp_at(t, rng);
    p.exposure = options_.exposure;
    const int n = r.points_per_profile;
    p.x_mm.assign(static_cast<std::size_t>(n), hal::kNoReturn);
    p.z_mm.assign(static_cast<std::size_t>(n), hal::kNoReturn);
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int k2 = 0; k2 < n; ++k2) {
      const auto i = static_cast<std::size_t>(k2);
      const Vector3d dir = r.ray_direction(k2, n);
      // Noise and ghosts move the point along its fan ray, as a wrong peak on the chip would.
      double range = std::isnan(truth.z_mm[i]) ? kNaN : std::hypot(truth.x_mm[i], truth.z_mm[i]);
      if (!std::isnan(range) && uniform(rng) < f.ghost_probability)
        range *= 1.0 + 0.2 * uniform(rng);
      if (!std::isnan(range) && f.range_noise_sigma_mm > 0.0)
        range += f.range_noise_sigma_mm * noise(rng);
      if (uniform(rng) < f.outlier_probability) {
        range = uniform(rng) < 0.5
                    ? kNaN
                    : (r.min_depth_mm + uniform(rng) * (r.max_depth_mm - r.min_depth_mm)) / dir.z();
      }
      if (std::isnan(range)) continue;
      double x = range * dir.x(), z = range * dir.z();
      if (options_.quantise) quantise_to_chip(r, k2, x, z);
      if (!r.depth_in_range(z)) continue;
      p.x_mm[i] = static_cast<float>(x);
      p.z_mm[i] = static_cast<float>(z);
    }
  }

 private:
  hal::Timestamp exposure_centre(std::uint64_t k) const {
    return tick(start_, options_.profile_rate_hz, k);
  }

  const RayCaster& caster_;
  const RangerOptions options_;
  const RangerPoseFn pose_;
  const hal::Timestamp start_;
};

}  // namespace

ProfileTruth cast_profile(const RayCaster& caster, const hal::StripeRanger& ranger,
                          const Eigen::Isometry3d& T_scene_ranger) {
  const int n = ranger.points_per_profile;
  const auto un = static_cast<std::size_t>(n);
  ProfileTruth t;
  t.x_mm.assign(un, kNaN);
  t.z_mm.assign(un, kNaN);
  t.point_scene.assign(un, Vector3d::Constant(kNaN));
  t.object.assign(un, -1);
  std::vector<Ray> rays(un);
  const Vector3d origin = T_scene_ranger.translation();
  for (int k = 0; k < n; ++k) {
    const Vector3d d = ranger.ray_direction(k, n);
    // Stop the ray where its depth leaves the camera's range.
    rays[static_cast<std::size_t>(k)] =
        Ray{origin, T_scene_ranger.linear() * d, 0.0, ranger.max_depth_mm / d.z()};
  }
  std::vector<Hit> hits(un);
  caster.cast(rays, hits);
  const Vector3d camera = T_scene_ranger * ranger.camera_point();
  std::vector<Ray> back;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < un; ++i) {
    if (!hits[i].valid) continue;
    const Vector3d p = T_scene_ranger.inverse() * hits[i].point;
    if (!ranger.depth_in_range(p.z())) continue;
    const Vector3d to_camera = camera - hits[i].point;
    back.push_back(
        Ray{hits[i].point, to_camera.normalized(), kSurfaceEps, to_camera.norm() - kSurfaceEps});
    index.push_back(i);
  }
  std::vector<std::uint8_t> blocked(back.size());
  caster.occluded(back, blocked);
  for (std::size_t j = 0; j < back.size(); ++j) {
    if (blocked[j]) continue;  // camera shadow
    const std::size_t i = index[j];
    const Vector3d p = T_scene_ranger.inverse() * hits[i].point;
    t.x_mm[i] = p.x();
    t.z_mm[i] = p.z();
    t.point_scene[i] = hits[i].point;
    t.object[i] = hits[i].object;
  }
  return t;
}

void quantise_to_chip(const hal::StripeRanger& ranger, int k, double& x_mm, double& z_mm) {
  const double row = (ranger.max_depth_mm - ranger.min_depth_mm) / kChipRows;
  const double zq = ranger.min_depth_mm + std::round((z_mm - ranger.min_depth_mm) / row) * row;
  x_mm = zq * std::tan(ranger.ray_angle(k, ranger.points_per_profile));
  z_mm = zq;
}

std::unique_ptr<hal::RangerSource> make_simulated_ranger(std::string name, const RayCaster& caster,
                                                         RangerOptions options, RangerPoseFn pose,
                                                         hal::Clock& clock, hal::Timestamp start) {
  return std::make_unique<RangerDevice>(std::move(name), caster, std::move(options),
                                        std::move(pose), clock, start);
}

}  // namespace rangefit::sim
