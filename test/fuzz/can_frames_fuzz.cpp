// CAN codecs as the drivers meet them on a bus: any sequence of frames (CiA 402, PowerCube and
// the profile ranger's segmented CAN FD stream) is decoded without a crash or a sanitizer
// report, and a profile encoded from the input reassembles to exactly what was sent.
#include <cstdlib>
#include <vector>

#include "drivers/can/can_frame.hpp"
#include "drivers/can/cia402_codec.hpp"
#include "drivers/can/powercube_codec.hpp"
#include "drivers/can/ranger_codec.hpp"
#include "test/fuzz/fuzz_bytes.hpp"

namespace {

using namespace rangefit::drivers::can;

// Frames as the transport hands them over: any id, any length up to 64, any flags.
void feed_bus_frames(rangefit::fuzz::ByteReader& in) {
  ranger::Reassembler reassembler;
  for (int i = 0; i < 64 && !in.empty(); ++i) {
    CanFrame frame;
    frame.id = in.take<std::uint16_t>() & 0x7FFu;
    frame.len = static_cast<std::uint8_t>(in.take<std::uint8_t>() % (CanFrame::kMaxData + 1));
    frame.flags = in.take<std::uint8_t>();
    const auto bytes = in.take_span(frame.len);
    std::copy(bytes.begin(), bytes.end(), frame.data.begin());
    (void)cia402::decode(frame);
    (void)powercube::decode(frame);
    const auto result = reassembler.feed(frame);
    if (result == ranger::FeedResult::kComplete &&
        reassembler.profile().point_count > ranger::kMaxPoints) {
      std::abort();  // a completed profile is bounded
    }
  }
}

// Encode -> reassemble round trip of a profile drawn from the input.
void round_trip(rangefit::fuzz::ByteReader& in) {
  ranger::WireProfile sent;
  sent.sequence = in.take<std::uint32_t>();
  sent.device_time_us = in.take<std::uint32_t>();
  sent.exposure_us = in.take<std::uint16_t>();
  // A profile carries 1..kMaxPoints values (an empty one is not sent).
  sent.point_count = static_cast<std::uint16_t>(1 + in.take<std::uint16_t>() % ranger::kMaxPoints);
  sent.latched_axis = in.take<std::int32_t>();
  sent.units_um = in.take<std::uint8_t>();
  sent.flags = in.take<std::uint8_t>();
  for (std::size_t k = 0; k < sent.point_count; ++k) sent.range[k] = in.take<std::uint16_t>();

  std::vector<CanFrame> frames(1 + ranger::kMaxSegments);
  const std::size_t n = ranger::encode(3, sent, frames);
  if (n == 0) std::abort();  // every point count in 1..kMaxPoints encodes
  ranger::Reassembler reassembler;
  ranger::FeedResult last = ranger::FeedResult::kPending;
  for (std::size_t k = 0; k < n; ++k) last = reassembler.feed(frames[k]);
  if (last != ranger::FeedResult::kComplete) std::abort();
  const auto& got = reassembler.profile();
  if (got.point_count != sent.point_count || got.latched_axis != sent.latched_axis ||
      got.flags != sent.flags || got.units_um != sent.units_um) {
    std::abort();
  }
  for (std::size_t k = 0; k < sent.point_count; ++k) {
    if (got.range[k] != sent.range[k]) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rangefit::fuzz::ByteReader bus(data, size);
  feed_bus_frames(bus);
  rangefit::fuzz::ByteReader profile(data, size);
  round_trip(profile);
  return 0;
}
