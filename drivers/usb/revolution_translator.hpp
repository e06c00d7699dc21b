#pragma once
// The CSS receive hot path: bytes of bulk transfers in, HAL revolutions with host stamps out.
// Parser (resync, CRC, gaps) + device clock translation, falling back to the transfer's completion
// stamp minus one period while the clock is not synchronised. Not thread-safe: the driver
// serialises feed() and add_exchange(). No logging, no allocation per revolution.

#include <cstdint>
#include <span>

#include "drivers/usb/css_stream_parser.hpp"
#include "drivers/usb/device_clock.hpp"
#include "hal/samples.hpp"

namespace rangefit::drivers::css_usb {

class RevolutionTranslator {
 public:
  explicit RevolutionTranslator(ClockOptions clock = {},
                                hal::Duration completion_latency = std::chrono::microseconds(500))
      : clock_(clock), completion_latency_(completion_latency) {}

  // Calls emit(const hal::CssRevolution&, const StreamParser::Frame&) per valid revolution.
  template <typename Emit>
  void feed(std::span<const std::uint8_t> bytes, hal::Timestamp completed, Emit&& emit) {
    parser_.feed(bytes, [&](const StreamParser::Frame& frame) {
      translate(frame.revolution, completed);
      emit(static_cast<const hal::CssRevolution&>(out_), frame);
    });
  }

  bool add_exchange(hal::Timestamp before, std::uint64_t device_us, hal::Timestamp after) {
    return clock_.add_exchange(before, device_us, after);
  }
  // Device restarted or replugged: drop partial data, sequence history and clock fit.
  void reset() {
    parser_.reset();
    clock_.reset();
  }

  const ParserCounters& counters() const { return parser_.counters(); }
  const DeviceClock& clock() const { return clock_; }
  std::uint64_t host_stamped() const { return host_stamped_; }

 private:
  void translate(const WireRevolution& r, hal::Timestamp completed);

  StreamParser parser_;
  DeviceClock clock_;
  hal::Duration completion_latency_;
  hal::CssRevolution out_;
  std::uint64_t host_stamped_ = 0;  // revolutions stamped from the completion time (no sync)
};

}  // namespace rangefit::drivers::css_usb
