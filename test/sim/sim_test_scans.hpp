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

// The axis samples and profiles of one full sweep of the stripe cell's linear axis through the
// laser plane (the true cell: o.geometry); started false when a simulated device refused to start.
struct RawStripeSweep {
  bool started = false;
  std::vector<hal::AxisSample> axis;
  std::vector<hal::RangerProfile> profiles;
};

inline RawStripeSweep record_stripe_sweep(const Scene& scene, const RayCaster& caster,
                                          const StripeCellOptions& o) {
  using std::chrono::milliseconds;
  SimClock clock;
  StripeCell cell(scene, caster, o, clock);
  RawStripeSweep raw;
  raw.started = cell.axis().enable() && cell.axis().start() && cell.ranger().start() &&
                cell.axis().move_to(o.geometry.axis_travel_mm, o.geometry.max_speed_mm_s);
  while (raw.started && !cell.axis().motion_complete()) {
    cell.axis().read(raw.axis, milliseconds(100));
    cell.ranger().read(raw.profiles, milliseconds(0));
  }
  return raw;
}

// That sweep fused as a cell that believes its geometry is `believed`.
inline fusion::FusedScan fuse_stripe_sweep(const RawStripeSweep& raw,
                                           const hal::StripeCellGeometry& believed) {
  if (!raw.started) {
    fusion::FusedScan failed;
    failed.bad = true;
    failed.reason = "simulated stripe cell did not start";
    return failed;
  }
  fusion::StripeCellFusionConfig config;
  config.geometry = believed;
  fusion::StripeCellAssembler assembler(config);
  assembler.begin_scan();
  for (const auto& s : raw.axis) assembler.add_axis(s);
  for (const auto& p : raw.profiles) assembler.add_profile(p);
  return assembler.finish();
}

// One full sweep of the stripe cell with its default geometry, fused; bad with a reason when a
// simulated device refuses to start.
inline fusion::FusedScan stripe_cell_scan(const Scene& scene, const RayCaster& caster,
                                          std::uint64_t seed) {
  StripeCellOptions o;
  o.seed = seed;
  return fuse_stripe_sweep(record_stripe_sweep(scene, caster, o), o.geometry);
}

// Every third point of a fused scan, moved into the scene frame by T.
inline std::vector<Eigen::Vector3d> thinned(const fusion::FusedScan& scan,
                                            const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < scan.cloud.size(); i += 3) points.push_back(T * scan.cloud.points[i]);
  return points;
}

}  // namespace rangefit::sim::testing
