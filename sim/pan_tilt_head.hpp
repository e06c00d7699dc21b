#pragma once
// Simulated mobile scanning head (thesis 5.2.1, fig. 5.14-5.16): the stripe ranger on a pan-tilt
// unit that sweeps the laser plane across the scene, pose by eq. 5.7-5.10
// (hal/pan_tilt_geometry.hpp). Two HAL devices: the ranger's profiles and the unit's pan/tilt
// angle samples. The sweep starts at clock.now(): pan runs from -sweep/2 to +sweep/2 at the
// sweep rate with tilt held, as in the thesis's table-top scans (50 deg at 10 deg/s).

#include <memory>
#include <vector>

#include "hal/pan_tilt_geometry.hpp"
#include "sim/ranger_simulator.hpp"

namespace rangefit::sim {

// A further camera of the head's laser plane with a ranger stream of its own: the same laser,
// fan and motion; `ranger` says where its camera looks from (baseline_mm < 0: the other side).
struct PanTiltCamera {
  hal::StripeRanger ranger;
  FaultOptions faults;
  std::uint64_t seed = 2;
};

struct PanTiltOptions {
  hal::PanTiltGeometry geometry;
  std::vector<PanTiltCamera> cameras;  // further cameras; all sweep with the one head
  double tilt_rad = 0.0;  // held during the sweep
  bool quantise = true;
  double angle_rate_hz = 100.0;  // pan/tilt position replies per second
  hal::Duration exposure = std::chrono::milliseconds(10);
  FaultOptions ranger_faults;
  FaultOptions angle_faults;  // stale readings, jitter, drops, disconnects
  std::uint64_t seed = 1;
};

class PanTiltHead {
 public:
  PanTiltHead(const Scene& scene, const RayCaster& caster, PanTiltOptions options,
              hal::Clock& clock);
  ~PanTiltHead();

  hal::RangerSource& ranger();
  // Camera k's ranger: 0 is ranger(), k >= 1 options().cameras[k - 1]'s.
  hal::RangerSource& ranger(std::size_t k);
  hal::PanTiltSource& angles();

  hal::Timestamp sweep_start() const { return start_; }
  hal::Timestamp sweep_end() const;
  double pan_at(hal::Timestamp t) const;  // reported pan (encoder), rad
  Eigen::Isometry3d T_scene_ranger(hal::Timestamp t) const;
  const PanTiltOptions& options() const { return options_; }

 private:
  class AngleDevice;
  const PanTiltOptions options_;
  const Eigen::Isometry3d T_scene_world_;
  const hal::Timestamp start_;
  std::vector<std::unique_ptr<hal::RangerSource>> rangers_;  // the first camera's, then the others'

  std::unique_ptr<AngleDevice> angles_;
};

}  // namespace rangefit::sim
