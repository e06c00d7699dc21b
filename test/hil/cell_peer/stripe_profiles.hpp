#pragma once
// What the stripe cell's ranger sees, as a function of where the linear axis has moved the table:
// the simulated cell's profiles (sim::cast_profile over the scene mounted as sim::StripeCell
// mounts it, depths quantised to the chip as the simulated ranger does, thesis 5.2.1), cast every
// step_mm of the axis travel and kept as the ranges the CAN FD profile carries. Ray casting under
// the VM's emulated CPU is slow, so the build casts once on the host (save) and the peer loads the
// recording; at each exposure the peer looks up the drive's exact position. Pure: no I/O after
// construction, no threads.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hal/stripe_geometry.hpp"

namespace rangefit::hil {

struct StripeProfileOptions {
  hal::StripeCellGeometry geometry;  // as the daemon's [fusion.stripe_cell] defaults
  double step_mm = 0.05;             // the axis' resolution (thesis 5.2.1)
  // Range LSB on the wire: 65535 x 10 µm covers the cell's depths (250..650 mm) finer than the
  // chip's rows ((650 - 250) / 1536 = 0.26 mm).
  std::uint8_t units_um = 10;
};

class StripeProfiles {
 public:
  // path: a scene file (cast over the axis travel) or a recording of save() ("*.profiles").
  explicit StripeProfiles(const std::string& path, StripeProfileOptions options = {});
  bool save(const std::string& path) const;
  // Why the scene or the recording could not be read; then size() is 0.
  const std::string& error() const { return error_; }

  std::size_t size() const { return points_ == 0 ? 0 : ranges_.size() / points_; }
  std::size_t points() const { return points_; }
  std::uint8_t units_um() const { return units_um_; }
  // The ranges the ranger measures with the axis at axis_mm: the nearest cast profile (the
  // travel's ends beyond it). out.size() must be points().
  void fill(double axis_mm, std::span<std::uint16_t> out) const;

 private:
  void cast(const std::string& scene_path, const StripeProfileOptions& options);
  void load(const std::string& path);

  std::vector<std::uint16_t> ranges_;  // size() profiles of points_ values, profile j at j step
  std::size_t points_ = 0;
  double step_mm_ = 0.0;
  std::uint8_t units_um_ = 0;
  std::string error_;
};

}  // namespace rangefit::hil
