#include "drivers/can/ranger_codec.hpp"

#include <algorithm>

#include "drivers/common/crc32.hpp"

namespace rangefit::drivers::can::ranger {

std::uint32_t range_crc(const WireProfile& p) {
  std::uint32_t crc = 0;
  const std::size_t n = std::min<std::size_t>(p.point_count, kMaxPoints);
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<std::uint8_t, 2> b{static_cast<std::uint8_t>(p.range[i]),
                                        static_cast<std::uint8_t>(p.range[i] >> 8)};
    crc = crc32(b, crc);
  }
  return crc;
}

std::size_t encode(std::uint8_t node, const WireProfile& p, std::span<CanFrame> out) {
  const std::size_t segs = segment_count(p.point_count);
  if (p.point_count == 0 || p.point_count > kMaxPoints || out.size() < segs + 1) return 0;
  const auto seq8 = static_cast<std::uint8_t>(p.sequence);
  std::array<std::uint8_t, 64> b{};
  b[0] = seq8;
  b[1] = 0;
  put_u32(b, 2, p.sequence);
  put_u32(b, 6, p.device_time_us);
  put_u16(b, 10, p.exposure_us);
  put_u16(b, 12, p.point_count);
  put_u32(b, 14, static_cast<std::uint32_t>(p.latched_axis));
  b[18] = p.units_um;
  b[19] = p.flags;
  b[20] = static_cast<std::uint8_t>(segs);
  put_u32(b, 21, range_crc(p));
  out[0] = make_fd_frame(profile_id(node), std::span(b.data(), kHeaderBytes));
  for (std::size_t s = 1; s <= segs; ++s) {
    b.fill(0);
    b[0] = seq8;
    b[1] = static_cast<std::uint8_t>(s);
    const std::size_t first = (s - 1) * kValuesPerSegment;
    const std::size_t n = std::min(kValuesPerSegment, p.point_count - first);
    for (std::size_t j = 0; j < n; ++j) put_u16(b, 2 + 2 * j, p.range[first + j]);
    out[s] = make_fd_frame(profile_id(node), std::span(b.data(), 2 + 2 * n));
  }
  return segs + 1;
}

void Reassembler::restart(std::uint8_t seq8, hal::Timestamp stamp) {
  active_ = true;
  have_header_ = false;
  seq8_ = seq8;
  received_ = 0;
  segments_ = 0;
  first_stamp_ = stamp;
}

void Reassembler::abandon() {
  if (active_) ++counters_.incomplete;
  active_ = false;
}

bool Reassembler::expire(hal::Timestamp now) {
  if (!active_ || now - first_stamp_ <= timeout_) return false;
  abandon();
  return true;
}

FeedResult Reassembler::feed(const CanFrame& f) {
  const auto d = f.payload();
  if (d.size() < 2 || d[1] > kMaxSegments) {
    ++counters_.bad_frames;
    return FeedResult::kBadFrame;
  }
  if (!active_ || d[0] != seq8_) {
    abandon();  // a new profile began before the previous one completed
    restart(d[0], f.stamp);
  }
  const std::uint8_t s = d[1];
  if (s == 0) {
    if (d.size() < kHeaderBytes) {
      ++counters_.bad_frames;
      return FeedResult::kBadFrame;
    }
    if (have_header_) {
      ++counters_.duplicates;
      return FeedResult::kDuplicate;
    }
    const std::uint16_t count = get_u16(d, 12);
    if (count == 0 || count > kMaxPoints || d[20] != segment_count(count)) {
      ++counters_.bad_frames;
      abandon();
      return FeedResult::kBadFrame;
    }
    profile_.sequence = get_u32(d, 2);
    profile_.device_time_us = get_u32(d, 6);
    profile_.exposure_us = get_u16(d, 10);
    profile_.point_count = count;
    profile_.latched_axis = static_cast<std::int32_t>(get_u32(d, 14));
    profile_.units_um = d[18];
    profile_.flags = d[19];
    segments_ = d[20];
    expected_crc_ = get_u32(d, 21);
    have_header_ = true;
    header_stamp_ = f.stamp;
  } else {
    if (received_ & (1u << s)) {
      ++counters_.duplicates;
      return FeedResult::kDuplicate;
    }
    // Segment lengths are only known against the header; store what the frame carries now and
    // check the length when the profile completes (segments may precede the header).
    const std::size_t first = (s - 1) * kValuesPerSegment;
    const std::size_t n = std::min(kValuesPerSegment, (d.size() - 2) / 2);
    for (std::size_t j = 0; j < n && first + j < kMaxPoints; ++j) {
      profile_.range[first + j] = get_u16(d, 2 + 2 * j);
    }
    if (n < kValuesPerSegment && first + n < kMaxPoints) {
      // Short frame: remember how far it reached by marking the rest as missing data.
      std::fill(profile_.range.begin() + static_cast<std::ptrdiff_t>(first + n),
                profile_.range.begin() +
                    static_cast<std::ptrdiff_t>(std::min(first + kValuesPerSegment, kMaxPoints)),
                kNoReturn);
    }
    received_ |= 1u << s;
  }
  if (!have_header_) return FeedResult::kPending;
  const std::uint32_t all = ((1u << (segments_ + 1)) - 1) & ~1u;
  if ((received_ & all) != all) return FeedResult::kPending;
  return finish();
}

FeedResult Reassembler::finish() {
  active_ = false;
  if ((received_ >> (segments_ + 1)) != 0) {  // segments beyond the header's count
    ++counters_.bad_frames;
    return FeedResult::kBadFrame;
  }
  if (range_crc(profile_) != expected_crc_) {
    ++counters_.crc_errors;
    return FeedResult::kCrcError;
  }
  ++counters_.complete;
  return FeedResult::kComplete;
}

}  // namespace rangefit::drivers::can::ranger
