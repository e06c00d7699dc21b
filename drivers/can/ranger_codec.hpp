#pragma once
// The project-defined CAN FD profile of the laser-stripe ranger (docs/protocols/can.md): one
// profile = a header frame (segment 0) and ceil(points/31) segment frames on 0x380+n, each
// [profile sequence U8, segment index U8, payload]. The reassembler collects segments without
// allocating, checks the CRC-32 of the range data and gives up on profiles that stay incomplete.

#include <array>
#include <cstdint>
#include <span>

#include "drivers/can/can_frame.hpp"
#include "hal/time.hpp"

namespace rangefit::drivers::can::ranger {

inline constexpr std::uint32_t profile_id(std::uint8_t node) { return 0x380u + node; }
inline constexpr std::size_t kMaxPoints = 512;
inline constexpr std::size_t kValuesPerSegment = 31;
inline constexpr std::size_t kMaxSegments =
    (kMaxPoints + kValuesPerSegment - 1) / kValuesPerSegment;
inline constexpr std::size_t kHeaderBytes = 2 + 23;  // padded to 32 on the wire
inline constexpr std::uint16_t kNoReturn = 0xFFFF;

enum WireFlags : std::uint8_t {
  kWireOverrun = 1u << 0,
  kWireSaturated = 1u << 1,
  kWireLaserOff = 1u << 2,
  kWireAxisValid = 1u << 3,  // latched_axis carries the linear axis position
};

struct WireProfile {
  std::uint32_t sequence = 0;
  std::uint32_t device_time_us = 0;  // exposure centre, device clock (wraps after ~71 min)
  std::uint16_t exposure_us = 0;
  std::uint16_t point_count = 0;                  // <= kMaxPoints
  std::int32_t latched_axis = 0;                  // axis increments at exposure (kWireAxisValid)
  std::uint8_t units_um = 1;                      // range LSB in micrometres
  std::uint8_t flags = 0;                         // WireFlags
  std::array<std::uint16_t, kMaxPoints> range{};  // kNoReturn = no return
};

inline std::size_t segment_count(std::size_t points) {
  return (points + kValuesPerSegment - 1) / kValuesPerSegment;
}

// CRC-32 over the first point_count range values as little-endian U16 bytes.
std::uint32_t range_crc(const WireProfile& p);

// Encodes p into out (needs 1 + segment_count frames); returns the number of frames written,
// 0 when out is too small or point_count is out of range.
std::size_t encode(std::uint8_t node, const WireProfile& p, std::span<CanFrame> out);

enum class FeedResult : std::uint8_t {
  kPending,    // frame taken, profile not complete yet
  kComplete,   // profile() holds a complete, CRC-checked profile
  kCrcError,   // all segments arrived but the CRC did not match; profile discarded
  kBadFrame,   // wrong length, segment index out of range, header inconsistent
  kDuplicate,  // segment already received for this profile
};

struct ReassemblyCounters {
  std::uint64_t complete = 0;
  std::uint64_t incomplete = 0;  // abandoned: timed out or superseded by the next profile
  std::uint64_t crc_errors = 0;
  std::uint64_t bad_frames = 0;
  std::uint64_t duplicates = 0;
};

class Reassembler {
 public:
  explicit Reassembler(hal::Duration timeout = std::chrono::milliseconds(50)) : timeout_(timeout) {}

  // Feeds one frame already known to carry this ranger's id.
  FeedResult feed(const CanFrame& frame);
  // Abandons a profile whose first frame is older than the timeout; true if one was dropped.
  bool expire(hal::Timestamp now);

  const WireProfile& profile() const { return profile_; }
  hal::Timestamp header_stamp() const { return header_stamp_; }  // receive stamp of segment 0
  const ReassemblyCounters& counters() const { return counters_; }

 private:
  void restart(std::uint8_t seq8, hal::Timestamp stamp);
  void abandon();
  FeedResult finish();

  hal::Duration timeout_;
  WireProfile profile_;
  bool active_ = false;
  bool have_header_ = false;
  std::uint8_t seq8_ = 0;
  std::uint32_t received_ = 0;  // bit s = segment s (1..17) present
  std::uint32_t expected_crc_ = 0;
  std::size_t segments_ = 0;
  hal::Timestamp first_stamp_{};
  hal::Timestamp header_stamp_{};
  ReassemblyCounters counters_;
};

}  // namespace rangefit::drivers::can::ranger
