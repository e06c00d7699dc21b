#pragma once
// Assemblers for the laser-stripe ranger (thesis 5.2.1): profiles plus
// the stream that moves the laser plane - linear-axis positions in the sensor cell, pan/tilt
// angles on the mobile head - interpolated at each profile's exposure centre. The cloud is
// organised profile x point (points_per_profile columns), one row per fused profile.
//
// Use: begin_scan(); feed pose samples (add_axis / add_pan_tilt) and profiles (add_profile) as
// they arrive, in any interleaving; finish() returns the scan. A profile is fused as soon as the
// pose stream reaches its stamp; it waits otherwise, at most limits.max_pending_frames profiles
// deep (then the oldest is fused with an extrapolated pose, counted). Not thread-safe.

#include <cstddef>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

#include "fusion/fused_scan.hpp"
#include "fusion/time_alignment.hpp"
#include "hal/pan_tilt_geometry.hpp"
#include "hal/samples.hpp"
#include "hal/stripe_geometry.hpp"

namespace rangefit::fusion {

// A further camera of the cell's laser plane (thesis 3.2.1, fig. 3.6b; the first is the
// geometry's ranger): the stripe device called `name` reports its profiles in its own frame of
// the plane and may see it from the other side.
struct StripeCameraConfig {
  std::string name;
  Eigen::Vector3d ranger_position_cell_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d ranger_rpy_cell_rad = Eigen::Vector3d::Zero();
  double baseline_mm = 0.0;  // camera offset from the laser plane along its y; < 0: other side
};

struct StripeCellFusionConfig {
  hal::StripeCellGeometry geometry{};
  std::vector<StripeCameraConfig> cameras;  // further cameras of the same laser plane
  // Expected profile period for the clock-jump check; zero: the step between the last two
  // profiles is expected.
  hal::Duration profile_period{};
  std::size_t expected_profiles = 8192;  // memory reserved per scan (400 mm at 0.05 mm steps)
  TimeLimits limits{};
};

// The cell as the stripe device `device` sees it: the geometry with its camera's pose and side
// when `cameras` names it, else unchanged.
inline StripeCellFusionConfig stripe_cell_for(const StripeCellFusionConfig& c,
                                              std::string_view device) {
  StripeCellFusionConfig out = c;
  for (const StripeCameraConfig& cam : c.cameras) {
    if (cam.name != device) continue;
    out.geometry.ranger_position_cell_mm = cam.ranger_position_cell_mm;
    out.geometry.ranger_rpy_cell_rad = cam.ranger_rpy_cell_rad;
    out.geometry.ranger.baseline_mm = cam.baseline_mm;
  }
  return out;
}

// The name of the device's camera in `cameras`, or empty when it is the first camera.
inline std::string stripe_camera_of(const StripeCellFusionConfig& c, std::string_view device) {
  for (const StripeCameraConfig& cam : c.cameras) {
    if (cam.name == device) return cam.name;
  }
  return {};
}

// A further camera of the pan-tilt head's laser plane: a pan_tilt device of its own whose
// profiles the head's laser and motion make, calibrated into the same laser-plane coordinates.
// Only where it looks from differs: its offset from the plane (< 0: the other side).
struct PanTiltCameraConfig {
  std::string name;
  double baseline_mm = 0.0;
};

struct PanTiltFusionConfig {
  hal::PanTiltGeometry geometry{};
  std::vector<PanTiltCameraConfig> cameras;  // further cameras of the same laser plane
  hal::Duration profile_period = std::chrono::milliseconds(10);  // 100 profiles/s (thesis)
  std::size_t expected_profiles = 512;  // 50 deg at 10 deg/s and 100 profiles/s = 500
  TimeLimits limits{};
};

// The head as the pan_tilt device `device` sees it: the ranger with its camera's offset when
// `cameras` names it, else unchanged.
inline PanTiltFusionConfig pan_tilt_for(const PanTiltFusionConfig& c, std::string_view device) {
  PanTiltFusionConfig out = c;
  for (const PanTiltCameraConfig& cam : c.cameras) {
    if (cam.name == device) out.geometry.ranger.baseline_mm = cam.baseline_mm;
  }
  return out;
}

// The part both assemblers share; the pose of the ranger comes from a derived class.
class ProfileAssembler {
 public:
  virtual ~ProfileAssembler() = default;
  void begin_scan();
  // Feeds one profile. Returns the number of profiles fused by this call.
  std::size_t add_profile(const hal::RangerProfile& profile);
  std::size_t pending() const { return pending_.size(); }
  const FusedScan& scan() const { return scan_; }
  // Fuses what still waits (extrapolating, counted), applies the fault limit, hands the scan
  // over. Call begin_scan() before the next scan.
  FusedScan finish();

 protected:
  ProfileAssembler(int columns, std::size_t expected_profiles, hal::Duration profile_period,
                   const TimeLimits& limits);
  // World from ranger for the interpolated pose channels v0, v1.
  virtual Eigen::Isometry3d T_world_ranger(double v0, double v1) const = 0;
  // Appends one pose sample and fuses the profiles it makes ready.
  std::size_t add_pose(hal::Timestamp stamp, double v0, double v1, bool valid);

 private:
  bool ready(const hal::RangerProfile& p) const;
  void fuse(const hal::RangerProfile& p);
  std::size_t drain(bool force);

  int columns_;
  std::size_t expected_profiles_;
  hal::Duration profile_period_;
  TimeLimits limits_;
  ReferenceTrack poses_;
  FrameCheck frame_check_;
  std::deque<hal::RangerProfile> pending_;
  FusedScan scan_;
};

// Sensor cell: p_table = T_world_ranger(axis position at the profile's stamp) * (x, 0, z).
class StripeCellAssembler final : public ProfileAssembler {
 public:
  explicit StripeCellAssembler(const StripeCellFusionConfig& config);
  std::size_t add_axis(const hal::AxisSample& sample) {
    return add_pose(sample.stamp, sample.position_mm, 0.0, sample.valid);
  }

 private:
  Eigen::Isometry3d T_world_ranger(double position_mm, double) const override {
    return config_.geometry.T_world_ranger(position_mm);
  }
  StripeCellFusionConfig config_;
};

// Mobile head: eq. 5.7 with pan and tilt interpolated at the profile's stamp.
class PanTiltAssembler final : public ProfileAssembler {
 public:
  explicit PanTiltAssembler(const PanTiltFusionConfig& config);
  std::size_t add_pan_tilt(const hal::PanTiltSample& sample) {
    return add_pose(sample.stamp, sample.pan_rad, sample.tilt_rad, sample.valid);
  }

 private:
  Eigen::Isometry3d T_world_ranger(double pan_rad, double tilt_rad) const override {
    return config_.geometry.T_world_ranger(pan_rad, tilt_rad);
  }
  PanTiltFusionConfig config_;
};

}  // namespace rangefit::fusion
