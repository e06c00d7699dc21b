#include "drivers/can/transport.hpp"

#include <algorithm>

namespace rangefit::drivers::can {

TransportCounters AtomicTransportCounters::snapshot() const {
  constexpr auto r = std::memory_order_relaxed;
  return {rx_frames.load(r),    tx_frames.load(r),  rx_overflow.load(r), tx_buffer_full.load(r),
          error_frames.load(r), bad_stamps.load(r), clock_steps.load(r), reopens.load(r)};
}

bool FrameFilter::accepts(std::uint32_t id) const {
  return ids.empty() || std::find(ids.begin(), ids.end(), id) != ids.end();
}

}  // namespace rangefit::drivers::can
