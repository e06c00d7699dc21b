#pragma once
// A simulated laser-stripe ranger on CAN FD: free-running at a configured rate, it sends each
// profile as the project-defined header + segment frames, stamps it with its own microsecond
// clock (offset from CLOCK_MONOTONIC, as a real device's would be) and sends heartbeats.
// Faults for tests: silence, a dropped segment, a corrupt CRC, skipped sequence numbers.

#include <atomic>
#include <functional>
#include <span>

#include "drivers/can/ranger_codec.hpp"
#include "test/support/can_bus.hpp"

namespace rangefit::sim {

struct SimRangerConfig {
  std::uint8_t node = 0x20;
  double rate_hz = 100.0;
  std::uint16_t points = 512;
  std::uint16_t exposure_us = 500;
  std::uint8_t units_um = 4;
  std::int64_t device_clock_offset_us = 123'456'789;  // device µs = monotonic µs - this (mod 2^32)
  std::uint16_t heartbeat_ms = 100;
};

// Fills a profile's range values (raw units, kNoReturn for no return) for the profile numbered
// `sequence`, exposed at host time `exposure` (its centre, CLOCK_MONOTONIC): what the scene in
// front of the device looks like then.
using ProfileFill =
    std::function<void(std::uint32_t sequence, hal::Timestamp exposure, std::span<std::uint16_t>)>;

class SimProfileRanger final : public SimCanDevice {
 public:
  // fill: the profiles' contents; default: a ramp.
  explicit SimProfileRanger(SimRangerConfig config, ProfileFill fill = nullptr);

  void on_frame(const drivers::can::CanFrame&, drivers::can::CanTransport&) override {}
  hal::Timestamp tick(hal::Timestamp now, drivers::can::CanTransport& bus) override;

  void set_silent(bool silent) { silent_ = silent; }
  void drop_segment_next(std::uint8_t segment) { drop_segment_ = segment; }
  void corrupt_crc_next() { corrupt_crc_ = true; }
  void skip_sequences(std::uint32_t n) { skip_ = n; }
  // Device time that profile `sequence` was stamped with (for tests checking the mapping).
  std::uint32_t device_time_of(hal::Timestamp exposure) const;
  std::uint64_t profiles_sent() const { return sent_; }

 private:
  SimRangerConfig config_;
  ProfileFill fill_;
  drivers::can::ranger::WireProfile profile_;
  std::uint32_t sequence_ = 0;
  hal::Timestamp next_profile_{};
  hal::Timestamp next_heartbeat_{};
  bool booted_ = false;
  std::atomic<bool> silent_{false}, corrupt_crc_{false};
  std::atomic<std::uint8_t> drop_segment_{0};
  std::atomic<std::uint32_t> skip_{0};
  std::atomic<std::uint64_t> sent_{0};
};

}  // namespace rangefit::sim
