#pragma once
// The laser-stripe ranger over CAN FD (project-defined profile, docs/protocols/can.md): the driver
// reassembles profiles from their segment frames, checks sequence and CRC, translates the
// device's exposure time to CLOCK_MONOTONIC and supervises the ranger's heartbeat.
//
// Device clock: offset = receive stamp of the header - device time, filtered as a running
// minimum (transport delay only ever adds) that may creep up slowly so drift is followed.

#include <memory>
#include <string>

#include "drivers/can/can_source.hpp"
#include "drivers/can/ranger_codec.hpp"

namespace rangefit::drivers::can {

struct RangerConfig {
  std::string name = "ranger";
  std::uint8_t node = 0x20;
  // Where column k of n lies in the laser plane. A fan laser (fan_angle_rad > 0, the geometry
  // of hal::StripeRanger that fusion and the simulator use): on the fan ray at
  // theta_k = -fan/2 + fan k / (n - 1) from the centre line, x = z tan(theta_k). A line sensor
  // with parallel columns (fan_angle_rad = 0): x = (k - (n - 1) / 2) lateral_pitch_mm.
  double fan_angle_rad = 0.0;
  double lateral_pitch_mm = 0.1;
  double range_offset_mm = 0.0;  // z = offset + raw * units
  hal::Duration incomplete_timeout = std::chrono::milliseconds(50);
  hal::Duration heartbeat_timeout = std::chrono::milliseconds(300);
  // How fast the clock-offset estimate may rise per profile (covers drift, forgets old minima).
  hal::Duration offset_creep = std::chrono::microseconds(2);
  std::size_t queue_capacity = 256;
  LoopConfig loop;
};

FrameFilter ranger_filter(const RangerConfig& config);

class RangerCanSource final : public CanSource<hal::RangerProfile> {
 public:
  RangerCanSource(RangerConfig config, std::unique_ptr<CanTransport> transport);
  ~RangerCanSource() override { stop(); }

 private:
  void on_start(hal::Timestamp now) override { last_heartbeat_ = now; }
  bool devices_faulted() const override { return !alive_; }
  hal::Timestamp on_tick(hal::Timestamp now) override;
  void on_frame(const CanFrame& frame) override;
  void on_link(bool up) override;
  void deliver_profile();
  std::size_t pending_incomplete();

  RangerConfig config_;
  ranger::Reassembler reassembler_;
  hal::RangerProfile scratch_;  // capacity reserved once; reused for every profile
  std::uint64_t incomplete_seen_ = 0;
  bool have_sequence_ = false;
  std::uint32_t last_sequence_ = 0;
  bool have_offset_ = false;
  std::int64_t offset_ns_ = 0;
  std::uint32_t last_device_us_ = 0;
  std::int64_t device_us_ = 0;  // unwrapped device time
  hal::Timestamp last_heartbeat_{};
  std::atomic<bool> alive_{true};
};

}  // namespace rangefit::drivers::can
