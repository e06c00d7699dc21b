#pragma once
// What a laser-stripe ranger sees as a function of one coordinate of the motion that carries it
// past the scene: the linear axis moving the stripe cell's table (mm), or the pan of the pan-tilt
// head (rad). The simulated cell's profiles (sim::cast_profile over the scene, the ranger posed as
// sim::StripeCell or sim::PanTiltHead poses it, depths quantised to the chip as the simulated
// ranger does, thesis 5.2.1), cast every `step` of the coordinate and kept as the ranges the CAN
// FD profile carries. Ray casting under the VM's emulated CPU is slow, so the build casts once on
// the host (save) and the peer loads the recording; at each exposure the peer looks up the
// coordinate's exact value. Pure: no I/O after construction, no threads.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "hal/pan_tilt_geometry.hpp"
#include "hal/stripe_geometry.hpp"
#include "test/support/can_profile_ranger.hpp"

namespace rangefit::sim {
struct Scene;
}

namespace rangefit::hil {

// The coordinates cast: start, start + step, ... (count of them), and where the ranger stands in
// the scene at each.
struct ProfileSweep {
  hal::StripeRanger ranger;
  double start = 0.0;
  double step = 0.05;
  std::size_t count = 0;
  // Range LSB on the wire: 65535 units must cover the ranger's depth range.
  std::uint8_t units_um = 10;
  std::function<Eigen::Isometry3d(const sim::Scene&, double coordinate)> T_scene_ranger;
};

// The stripe cell (sim::StripeCell): the scene rides on the table ([sensors.stripe] mount), the
// ranger stands in the cell; the coordinate is the axis position over its travel, every 0.05 mm
// (the axis' resolution). 65535 x 10 µm covers the cell's depths (250..650 mm) finer than the
// chip's rows ((650 - 250) / 1536 = 0.26 mm).
ProfileSweep stripe_cell_sweep(const hal::StripeCellGeometry& geometry = {});
// The pan-tilt head (sim::PanTiltHead): the head at the scene's [sensors.pantilt] mount, tilt
// held at tilt_rad; the coordinate is the reported pan over pan_zero +- half_rad (and a margin),
// every step_rad. 65535 x 50 µm covers its depths (344..2685 mm).
ProfileSweep pan_tilt_sweep(const hal::PanTiltGeometry& geometry, double half_rad,
                            double tilt_rad = 0.0, double step_rad = 5e-5);

class StripeProfiles {
 public:
  // path: a recording of save() ("*.profiles"), or a scene file cast over `sweep`.
  explicit StripeProfiles(const std::string& path, const ProfileSweep& sweep = stripe_cell_sweep());
  bool save(const std::string& path) const;
  // Why the scene or the recording could not be read; then size() is 0.
  const std::string& error() const { return error_; }

  std::size_t size() const { return points_ == 0 ? 0 : ranges_.size() / points_; }
  std::size_t points() const { return points_; }
  std::uint8_t units_um() const { return units_um_; }
  // The ranges the ranger measures at `coordinate`: the nearest cast profile (the first or last
  // beyond the cast range). out.size() must be points().
  void fill(double coordinate, std::span<std::uint16_t> out) const;

 private:
  void cast(const std::string& scene_path, const ProfileSweep& sweep);
  void load(const std::string& path);

  std::vector<std::uint16_t> ranges_;  // size() profiles of points_ values, profile j at j step
  std::size_t points_ = 0;
  double start_ = 0.0;
  double step_ = 0.0;
  std::uint8_t units_um_ = 0;
  std::string error_;
};

// The CAN ranger that streams `profiles`: its node and rate, their points and units.
sim::SimRangerConfig ranger_config(const StripeProfiles& profiles, std::uint8_t node,
                                   double rate_hz);

}  // namespace rangefit::hil
