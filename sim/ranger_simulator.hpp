#pragma once
// The laser-stripe ranger as a simulated HAL device, shared by the stripe cell and the pan-tilt
// head (thesis 5.2.1): each profile casts the fan's 512 rays (hal/stripe_geometry.hpp) from the
// ranger's pose at the exposure centre. The first surface a fan ray meets is lit (so laser shadows
// fall out of the casting); it becomes a point only when the segment to the camera is clear
// (camera shadows) and its depth is inside the camera's range. Depths are quantised like the
// 1536 x 512 chip of the MAPP ranger: one profile point per chip column, the depth rounded to one
// of 1536 rows spread over the depth range, the point kept on its fan ray.

#include <functional>
#include <memory>
#include <vector>

#include "hal/source.hpp"
#include "hal/stripe_geometry.hpp"
#include "sim/fault_options.hpp"
#include "sim/ray_caster.hpp"

namespace rangefit::sim {

inline constexpr int kChipRows = 1536;

// One profile before noise, in double. Every vector has points_per_profile entries indexed by the
// fan ray k (the profile's column): point_scene[k] is the scene point of (x_mm[k], z_mm[k]).
// Where column k has no point, x_mm[k], z_mm[k] and point_scene[k] are NaN and object[k] is -1.
struct ProfileTruth {
  std::vector<double> x_mm, z_mm;            // ranger frame (laser plane y = 0)
  std::vector<Eigen::Vector3d> point_scene;  // scene frame, mm
  std::vector<int> object;                   // hit object, -1 = none
};

ProfileTruth cast_profile(const RayCaster& caster, const hal::StripeRanger& ranger,
                          const Eigen::Isometry3d& T_scene_ranger);

// Depth rounded to the chip's row grid, x moved along the same fan ray.
void quantise_to_chip(const hal::StripeRanger& ranger, int k, double& x_mm, double& z_mm);

struct RangerOptions {
  hal::StripeRanger ranger;
  double profile_rate_hz = 100.0;  // thesis: up to 100 profiles/s
  hal::Duration exposure = std::chrono::milliseconds(10);
  bool quantise = true;  // chip quantisation (off for exactness tests)
  FaultOptions faults;
  std::uint64_t seed = 1;
};

// Pose of the ranger in the scene at a time (the axis or the pan-tilt unit moves it).
using RangerPoseFn = std::function<Eigen::Isometry3d(hal::Timestamp)>;

// The simulated ranger device; profile k has its exposure centre at start + k / rate.
std::unique_ptr<hal::RangerSource> make_simulated_ranger(std::string name, const RayCaster& caster,
                                                         RangerOptions options, RangerPoseFn pose,
                                                         hal::Clock& clock, hal::Timestamp start);

}  // namespace rangefit::sim
