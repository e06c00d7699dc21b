#pragma once
// CSS assembler (thesis 4.2.1, eq. 4.17-4.21): turns revolutions of the
// Circular Scanning Sensor and the robot's last-joint angle stream into a world-frame cloud,
// organised revolution x 512, while the scan runs.
//
// Timing model: sample i of a revolution was taken at stamp + i * period / 512, i.e. i/512 of
// the way from its index pulse to the next one, the device-measured period being that distance
// (the previous stamp step, or the configured nominal period, when the device reports none).
// The path angle at that instant is omega = joint angle - omega_zero, linearly interpolated in
// the joint stream; without a joint stream, eq. 4.21's start/end-stamp method gives omega
// from -delta at t_start to +delta at t_end. World point: eq. 4.17 via CssGeometry.
//
// Use: begin_scan(); then, as they arrive, add_joint() for every joint sample and
// add_revolution() for every revolution (any interleaving); finish() returns the scan. A
// revolution is fused as soon as the joint stream covers its last sample, so with the usual
// ordering (joint samples arrive continuously) it is fused inside add_revolution().
// Not thread-safe: feed it from one thread.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <numbers>
#include <vector>

#include "fusion/fused_scan.hpp"
#include "fusion/time_alignment.hpp"
#include "hal/css_geometry.hpp"
#include "hal/samples.hpp"

namespace rangefit::fusion {

enum class OmegaSource {
  kJointStream,     // omega interpolated in the joint stream at each sample's instant
  kStartEndStamps,  // eq. 4.21: constant rate between the scan's start and end stamps
};

struct CssFusionConfig {
  hal::CssGeometry geometry{};  // eq. 4.17-4.20, thesis values as defaults
  OmegaSource omega_source = OmegaSource::kJointStream;
  std::uint8_t joint = 6;       // id of the joint whose angle is omega (JointSample::joint)
  double omega_zero_rad = 0.0;  // joint angle at the scan centre: omega = angle - omega_zero
  double deflection_rad = 5.0 * std::numbers::pi / 180.0;  // delta: the scan spans +-delta
  double scan_speed_mm_s = 2.0;  // v of eq. 4.21, when the end stamp is not known in advance
  hal::Duration nominal_period = std::chrono::nanoseconds(1'000'000'000 / 7);  // 7 Hz
  std::size_t expected_revolutions = 180;  // reserved per scan: 2*delta*R/v = 25 s at 7 Hz
  TimeLimits limits{};
};

class CssAssembler {
 public:
  explicit CssAssembler(const CssFusionConfig& config);

  // Starts a scan: forgets everything of the last one and reserves memory for
  // expected_revolutions. For OmegaSource::kStartEndStamps, t_start is the stamp at
  // omega = -delta and t_end the one at +delta (measured or planned); a zero t_start means
  // "the first revolution's stamp", a zero t_end means "at the configured scan speed".
  void begin_scan(hal::Timestamp t_start = {}, hal::Timestamp t_end = {});

  // Feeds one joint sample; samples of other joints are ignored. Returns the number of waiting
  // revolutions this made fusable (and fused).
  std::size_t add_joint(const hal::JointSample& sample);
  // Feeds one revolution. Returns the number of revolutions fused by this call.
  std::size_t add_revolution(const hal::CssRevolution& revolution);

  // Revolutions waiting for the joint stream to reach their last sample.
  std::size_t pending() const { return pending_.size(); }
  // The scan so far (rows fused up to now); valid until the next call.
  const FusedScan& scan() const { return scan_; }
  // Fuses what still waits (extrapolating, counted), applies the fault limit and hands the scan
  // over. Call begin_scan() before the next scan.
  FusedScan finish();

 private:
  struct Pending {
    hal::CssRevolution revolution;
    hal::Duration period;  // index pulse to the next one
  };
  bool ready(const hal::CssRevolution& rev, hal::Duration period) const;
  void fuse(const hal::CssRevolution& rev, hal::Duration period);
  std::size_t drain(bool force);

  CssFusionConfig config_;
  std::vector<Eigen::Vector3d> beam_mount_;  // R_x(eta) * beam direction of sample i
  Eigen::Vector3d laser_mount_;              // R_x(eta) * p_LD + t (eq. 4.17 inner part)
  ReferenceTrack joints_;
  FrameCheck frame_check_;
  std::deque<Pending> pending_;
  bool has_last_ = false;
  hal::Timestamp last_stamp_{};  // of the last accepted revolution
  std::uint32_t last_sequence_ = 0;
  hal::Duration last_period_{};    // device period of the last accepted revolution
  hal::Duration last_step_{};      // stamp step per revolution between the last two accepted
  bool start_from_first_ = false;  // eq. 4.21 fallback: t_start is the first revolution's stamp
  hal::Timestamp t_start_{};
  double omega_rate_ = 0.0;  // rad/ns for the eq. 4.21 fallback
  hal::Timestamp t_end_{};
  bool end_known_ = false;
  FusedScan scan_;
};

// Fuses a whole recorded scan in one call (tests, benchmarks, offline tools).
FusedScan fuse_css_scan(const CssFusionConfig& config,
                        const std::vector<hal::CssRevolution>& revolutions,
                        const std::vector<hal::JointSample>& joints, hal::Timestamp t_start = {},
                        hal::Timestamp t_end = {});

}  // namespace rangefit::fusion
