#pragma once
// Simulated scans fused from the raw HAL streams as on the cell, shared by the sim tests that
// hand them to the detectors.

#include <chrono>
#include <cstdint>
#include <vector>

#include "fusion/profile_assembler.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::sim::testing {

// One full sweep of the stripe cell's linear axis through the laser plane, fused; bad with a
// reason when a simulated device refuses to start.
inline fusion::FusedScan stripe_cell_scan(const Scene& scene, const RayCaster& caster,
                                          std::uint64_t seed) {
  using std::chrono::milliseconds;
  SimClock clock;
  StripeCellOptions o;
  o.seed = seed;
  StripeCell cell(scene, caster, o, clock);
  fusion::StripeCellFusionConfig config;
  config.geometry = o.geometry;
  fusion::StripeCellAssembler assembler(config);
  assembler.begin_scan();
  if (!cell.axis().enable() || !cell.axis().start() || !cell.ranger().start() ||
      !cell.axis().move_to(o.geometry.axis_travel_mm, o.geometry.max_speed_mm_s)) {
    fusion::FusedScan failed;
    failed.bad = true;
    failed.reason = "simulated stripe cell did not start";
    return failed;
  }
  std::vector<hal::RangerProfile> profiles;
  std::vector<hal::AxisSample> axis;
  while (!cell.axis().motion_complete()) {
    profiles.clear();
    axis.clear();
    cell.axis().read(axis, milliseconds(100));
    cell.ranger().read(profiles, milliseconds(0));
    for (const auto& s : axis) assembler.add_axis(s);
    for (const auto& p : profiles) assembler.add_profile(p);
  }
  return assembler.finish();
}

// Every third point of a fused scan, moved into the scene frame by T.
inline std::vector<Eigen::Vector3d> thinned(const fusion::FusedScan& scan,
                                            const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < scan.cloud.size(); i += 3) points.push_back(T * scan.cloud.points[i]);
  return points;
}

}  // namespace rangefit::sim::testing
