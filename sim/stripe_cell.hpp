#pragma once
// Simulated sensor cell (thesis 5.2.1, fig. 5.8): a static laser-stripe ranger above a
// measurement table that a linear axis (FESTO, up to 6.3 mm/s, 0.05 mm resolution) moves
// through the laser plane. Two HAL devices: the ranger's profile stream and the linear axis,
// which takes motion commands and reports its position as axis samples. The scene's objects
// ride on the table: the scene frame is the cell's table frame placed by Scene::mounts.

#include <memory>
#include <mutex>
#include <vector>

#include "hal/stripe_geometry.hpp"
#include "sim/ranger_simulator.hpp"

namespace rangefit::sim {

// A further camera of the cell's laser plane (thesis fig. 3.6b) with a ranger stream of its own:
// its geometry places its ranger frame and camera; the axis it rides is the cell's.
struct StripeCellCamera {
  hal::StripeCellGeometry geometry;
  FaultOptions faults;
  std::uint64_t seed = 2;
};

struct StripeCellOptions {
  hal::StripeCellGeometry geometry;
  std::vector<StripeCellCamera> cameras;  // further cameras; all sweep with the one axis
  double profile_rate_hz = 12.6;  // 0.5 mm profile spacing at 6.3 mm/s (thesis resolution)
  bool quantise = true;
  double axis_poll_hz = 50.0;        // position requests per second
  double axis_resolution_mm = 0.05;  // thesis: 0.05 mm
  hal::Duration axis_round_trip = std::chrono::milliseconds(4);
  FaultOptions ranger_faults;
  FaultOptions axis_faults;  // stale readings, jitter, dropped replies, disconnects
  std::uint64_t seed = 1;
};

// Motion of the axis: constant-speed moves (the thesis's scans run at constant table speed).
class AxisMotion {
 public:
  AxisMotion(double max_speed_mm_s, double travel_mm)
      : max_speed_(max_speed_mm_s), travel_(travel_mm) {}
  double position(hal::Timestamp t) const;
  double velocity(hal::Timestamp t) const;
  hal::Status move(hal::Timestamp now, double target_mm, double speed_mm_s);
  void halt(hal::Timestamp now);
  bool done(hal::Timestamp now) const;

 private:
  double position_locked(hal::Timestamp t) const;
  mutable std::mutex mutex_;
  const double max_speed_;
  const double travel_;
  hal::Timestamp t0_{};
  double p0_ = 0.0, target_ = 0.0, speed_ = 0.0;
};

class StripeCell {
 public:
  // The devices' time starts at clock.now(); caster must outlive the cell.
  StripeCell(const Scene& scene, const RayCaster& caster, StripeCellOptions options,
             hal::Clock& clock);
  ~StripeCell();

  hal::RangerSource& ranger();
  // Camera k's ranger: 0 is ranger(), k >= 1 options().cameras[k - 1]'s.
  hal::RangerSource& ranger(std::size_t k);
  hal::LinearAxis& axis();
  // Exact axis position at t (what the axis samples quantise).
  double axis_position(hal::Timestamp t) const { return motion_.position(t); }
  Eigen::Isometry3d T_scene_ranger(hal::Timestamp t) const;
  Eigen::Isometry3d T_scene_ranger(const hal::StripeCellGeometry& camera, hal::Timestamp t) const;
  const StripeCellOptions& options() const { return options_; }

 private:
  class AxisDevice;
  const StripeCellOptions options_;
  const Eigen::Isometry3d T_scene_world_;
  AxisMotion motion_;
  std::vector<std::unique_ptr<hal::RangerSource>> rangers_;  // the first camera's, then the others'
  std::unique_ptr<AxisDevice> axis_;
};

}  // namespace rangefit::sim
