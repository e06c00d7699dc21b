#pragma once
// Streaming parser for the CSS bulk stream. Transfers normally carry exactly one frame, but short
// transfers, split or concatenated frames and garbage all occur; the parser buffers bytes, finds
// the magic word, checks n and the CRC, and resynchronises on the next magic after anything bad.
// Sequence numbers are checked for gaps. Pure: no I/O, no allocation after the first frames.

#include <cstdint>
#include <span>
#include <vector>

#include "drivers/usb/css_protocol.hpp"

namespace rangefit::drivers::css_usb {

struct ParserCounters {
  std::uint64_t frames = 0;           // valid frames delivered
  std::uint64_t crc_errors = 0;       // frames with a magic word but a bad CRC or n
  std::uint64_t resyncs = 0;          // times the parser had to search for the next magic word
  std::uint64_t discarded_bytes = 0;  // bytes skipped while searching
  std::uint64_t gaps = 0;             // revolutions missing between consecutive sequence numbers
  std::uint64_t discontinuities = 0;  // sequence went backwards or jumped too far (device restart)
};

class StreamParser {
 public:
  // A jump of more than this many revolutions is a device restart, not lost data.
  static constexpr std::uint32_t kMaxGap = 1000;

  struct Frame {
    const WireRevolution& revolution;
    std::uint32_t missing_before;  // revolutions lost since the previous frame (0 normally)
    bool discontinuity;            // first frame after a restart (or the very first frame)
  };

  StreamParser() { buffer_.reserve(2 * kFrameBytes); }

  // Consumes bytes; calls on_frame(const Frame&) for every valid frame completed by them.
  template <typename OnFrame>
  void feed(std::span<const std::uint8_t> bytes, OnFrame&& on_frame) {
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
    std::size_t pos = 0;
    while (buffer_.size() - pos >= kMagic.size()) {
      if (!starts_with_magic(pos)) {
        pos = skip_to_magic(pos);
        continue;
      }
      if (buffer_.size() - pos < kFrameBytes) break;  // wait for the rest of the frame
      const auto decoded = decode_revolution(std::span(buffer_).subspan(pos, kFrameBytes));
      if (!decoded) {
        ++counters_.crc_errors;
        pos = skip_to_magic(pos + 1);
        continue;
      }
      pos += kFrameBytes;
      searching_ = false;
      revolution_ = *decoded;
      on_frame(sequence_check(revolution_));
    }
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(pos));
  }

  // Drops partial data and forgets the last sequence number (unplug, stream restart).
  void reset() {
    buffer_.clear();
    have_sequence_ = false;
    searching_ = false;
  }

  const ParserCounters& counters() const { return counters_; }

 private:
  bool starts_with_magic(std::size_t pos) const {
    for (std::size_t i = 0; i < kMagic.size(); ++i) {
      if (buffer_[pos + i] != kMagic[i]) return false;
    }
    return true;
  }

  // Position of the next magic word at or after `from` (or of a possible partial one at the end).
  std::size_t skip_to_magic(std::size_t from) {
    std::size_t pos = from;
    while (buffer_.size() - pos >= kMagic.size() && !starts_with_magic(pos)) ++pos;
    if (buffer_.size() - pos < kMagic.size()) {
      // Keep a tail that may be the start of a magic word split across transfers.
      while (pos < buffer_.size() && buffer_[pos] != kMagic[0]) ++pos;
    }
    if (pos > from) {
      counters_.discarded_bytes += pos - from;
      if (!searching_) ++counters_.resyncs;  // one resync per search, however long it takes
      searching_ = true;
    }
    return pos;
  }

  Frame sequence_check(const WireRevolution& r) {
    ++counters_.frames;
    const std::uint32_t expected = last_sequence_ + 1;
    const std::uint32_t ahead = r.sequence - expected;  // modulo 2^32: sequence may wrap
    const bool first = !have_sequence_;
    have_sequence_ = true;
    last_sequence_ = r.sequence;
    if (first) return {r, 0, true};
    if (ahead == 0) return {r, 0, false};
    if (ahead <= kMaxGap) {
      counters_.gaps += ahead;
      return {r, ahead, false};
    }
    ++counters_.discontinuities;
    return {r, 0, true};
  }

  std::vector<std::uint8_t> buffer_;
  WireRevolution revolution_;
  ParserCounters counters_;
  std::uint32_t last_sequence_ = 0;
  bool have_sequence_ = false;
  bool searching_ = false;  // skipping bytes in search of a magic word
};

}  // namespace rangefit::drivers::css_usb
