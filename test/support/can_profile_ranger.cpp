#include "test/support/can_profile_ranger.hpp"

#include <array>

#include "drivers/can/cia402_codec.hpp"

namespace rangefit::sim {

namespace can = drivers::can;

SimProfileRanger::SimProfileRanger(SimRangerConfig config, ProfileFill fill)
    : config_(config), fill_(std::move(fill)) {}

std::uint32_t SimProfileRanger::device_time_of(hal::Timestamp exposure) const {
  const std::int64_t us = exposure.count() / 1000 - config_.device_clock_offset_us;
  return static_cast<std::uint32_t>(us);
}

hal::Timestamp SimProfileRanger::tick(hal::Timestamp now, can::CanTransport& bus) {
  const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / config_.rate_hz));
  if (silent_) return now + std::chrono::milliseconds(5);
  if (!booted_) {
    (void)bus.send(can::cia402::encode_heartbeat(config_.node, can::cia402::kBootUp));
    booted_ = true;
    next_profile_ = now;
    next_heartbeat_ = now;
  }
  if (now >= next_heartbeat_) {
    (void)bus.send(can::cia402::encode_heartbeat(config_.node, can::cia402::kOperational));
    next_heartbeat_ = now + std::chrono::milliseconds(config_.heartbeat_ms);
  }
  if (now >= next_profile_) {
    sequence_ += 1 + skip_.exchange(0);
    profile_.sequence = sequence_;
    // Exposure is timed by the device's own clock: the centre lies half an exposure before
    // the scheduled read-out slot, however late the bus thread gets to send it.
    const hal::Timestamp exposure =
        next_profile_ - std::chrono::microseconds(config_.exposure_us / 2);
    profile_.device_time_us = device_time_of(exposure);
    profile_.exposure_us = config_.exposure_us;
    profile_.point_count = config_.points;
    profile_.units_um = config_.units_um;
    profile_.flags = 0;
    const std::span<std::uint16_t> range(profile_.range.data(), config_.points);
    if (fill_) {
      fill_(sequence_, exposure, range);
    } else {
      for (std::size_t k = 0; k < range.size(); ++k) {
        range[k] = static_cast<std::uint16_t>(10'000 + k + (sequence_ % 100));
      }
    }
    std::array<can::CanFrame, can::ranger::kMaxSegments + 1> frames;
    const std::size_t n = can::ranger::encode(config_.node, profile_, frames);
    if (corrupt_crc_.exchange(false)) frames[0].data[21] ^= 0xFF;
    const std::uint8_t drop = drop_segment_.exchange(0);
    for (std::size_t i = 0; i < n; ++i) {
      if (drop != 0 && i == drop) continue;
      (void)bus.send(frames[i]);
    }
    ++sent_;
    // The device's clock is steady: a late bus thread sends the slots it owes back to back,
    // each with its own exposure time. After a stall of more than kCatchUp slots the device
    // has overrun its buffer; it numbers the exposures it lost, so the driver sees a gap.
    constexpr int kCatchUp = 10;
    next_profile_ += period;
    if (now - next_profile_ > kCatchUp * period) {
      const auto lost = (now - next_profile_) / period;
      sequence_ += static_cast<std::uint32_t>(lost);
      next_profile_ += lost * period;
    }
  }
  return std::min(next_profile_, next_heartbeat_);
}

}  // namespace rangefit::sim
