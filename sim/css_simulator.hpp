#pragma once
// Simulated Circular Scanning Sensor on the robot's last joint (thesis 4.2.1, fig. 4.14-4.16).
// The joint pivots the sensor from omega = -delta to +delta at the TCP speed v (eq. 4.21) while
// the beam turns at 7 Hz; every sample is a ray from the laser point p_LD through the 27 mm scan
// circle (hal/css_geometry.hpp), valid only when the hit lies within 65-130 mm and the return ray
// from the hit to the CCD point p_CCD is unobstructed. Two HAL devices come out of one rig, as on
// the cell: the CSS revolution stream and the robot's joint-angle stream.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "hal/css_geometry.hpp"
#include "hal/source.hpp"
#include "sim/fault_options.hpp"
#include "sim/ray_caster.hpp"

namespace rangefit::sim {

struct CssScanOptions {
  hal::CssGeometry geometry;
  double deflection_rad = 5.0 * 3.14159265358979323846 / 180.0;  // delta (thesis: 5 deg)
  double speed_mm_s = 2.0;       // TCP speed v along the path (eq. 4.21); ~25 s per scan
  double rotation_hz = 7.0;      // beam revolutions per second
  double joint_rate_hz = 250.0;  // joint-angle samples per second (robot controller cycle)
  std::uint8_t joint_id = 6;     // the robot's last joint
  FaultOptions css_faults;       // range noise, outliers, ghosts, dropped revolutions, ...
  FaultOptions joint_faults;     // stamp jitter, stale readings, dropped samples, ...
  std::uint64_t seed = 1;
  // Where the robot holds the joint: the CSS world frame (the joint at omega = 0) in the scene.
  // Unset: the scene's CSS mount.
  std::optional<Eigen::Isometry3d> T_scene_world;
};

// Noise-free result of one revolution, in double: for the tests and the ground truth. Every
// array is indexed by the sample number i of the revolution; where sample i has no return,
// range_mm[i], point_scene[i] and normal_scene[i] are NaN and object[i] is -1.
struct CssRevolutionTruth {
  std::array<double, hal::CssRevolution::kSamples> range_mm{};
  std::array<Eigen::Vector3d, hal::CssRevolution::kSamples> point_scene;  // scene frame, mm
  std::array<double, hal::CssRevolution::kSamples> omega_rad{};  // path angle at each sample
  std::array<int, hal::CssRevolution::kSamples> object{};        // hit object, -1 = none
  std::array<Eigen::Vector3d, hal::CssRevolution::kSamples> normal_scene;  // unit, scene frame
};

class CssRig {
 public:
  // The scan starts at clock.now(). caster must outlive the rig and be built from `scene`.
  CssRig(const Scene& scene, const RayCaster& caster, CssScanOptions options, hal::Clock& clock);
  ~CssRig();

  hal::CssSource& css();
  hal::JointSource& joint();

  hal::Timestamp scan_start() const { return start_; }
  hal::Timestamp scan_end() const;  // joint reaches +delta
  double revolution_period_s() const { return 1.0 / options_.rotation_hz; }
  std::uint64_t revolutions_in_scan() const;
  // Path angle of the last joint at time t (clamped to [-delta, +delta]).
  double omega_at(hal::Timestamp t) const;
  hal::Timestamp revolution_stamp(std::uint64_t k) const;
  // Revolution k exactly as the sensor sees it, before noise and quantisation.
  CssRevolutionTruth cast_revolution(std::uint64_t k) const;
  const CssScanOptions& options() const { return options_; }
  const RayCaster& caster() const { return caster_; }

 private:
  class CssDevice;
  class JointDevice;
  const RayCaster& caster_;
  const CssScanOptions options_;
  const Eigen::Isometry3d T_scene_world_;
  const hal::Timestamp start_;
  std::unique_ptr<CssDevice> css_;
  std::unique_ptr<JointDevice> joint_;
};

}  // namespace rangefit::sim
