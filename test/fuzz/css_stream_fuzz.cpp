// The CSS bulk stream as it arrives over USB: garbage, split and concatenated transfers never
// crash the parser, and a revolution drawn from the input, sent after garbage in transfers of
// any size, comes out exactly as it went in.
#include <algorithm>
#include <cstdlib>
#include <vector>

#include "drivers/usb/css_protocol.hpp"
#include "drivers/usb/css_stream_parser.hpp"
#include "test/fuzz/fuzz_bytes.hpp"

namespace {

using namespace rangefit::drivers::css_usb;

void feed_in_transfers(StreamParser& parser, std::span<const std::uint8_t> stream,
                       std::size_t transfer, std::vector<WireRevolution>& got) {
  for (std::size_t pos = 0; pos < stream.size(); pos += transfer) {
    const auto chunk = stream.subspan(pos, std::min(transfer, stream.size() - pos));
    parser.feed(chunk, [&](const StreamParser::Frame& f) { got.push_back(f.revolution); });
  }
}

bool same(const WireRevolution& a, const WireRevolution& b) {
  if (a.sequence != b.sequence || a.device_time_us != b.device_time_us ||
      a.period_us != b.period_us || a.flags != b.flags) {
    return false;
  }
  for (std::size_t k = 0; k < kSamples; ++k) {
    if (a.samples[k].range_um != b.samples[k].range_um ||
        a.samples[k].intensity != b.samples[k].intensity ||
        a.samples[k].quality != b.samples[k].quality) {
      return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rangefit::fuzz::ByteReader in(data, size);
  const std::size_t transfer = 1 + in.take<std::uint16_t>() % (2 * kFrameBytes);
  const std::size_t garbage = in.take<std::uint16_t>() % 4096;
  (void)decode_info(in.rest());

  // Raw input as a stream.
  StreamParser raw;
  std::vector<WireRevolution> ignored;
  feed_in_transfers(raw, in.rest(), transfer, ignored);

  // Garbage, then one encoded revolution: exactly that revolution is the last frame out.
  WireRevolution sent;
  sent.sequence = in.take<std::uint32_t>();
  sent.device_time_us = in.take<std::uint64_t>();
  sent.period_us = in.take<std::uint32_t>();
  sent.flags = in.take<std::uint16_t>();
  for (auto& s : sent.samples) s = {in.take<std::uint16_t>(), in.take<std::uint8_t>(), 0};
  std::vector<std::uint8_t> stream(data, data + std::min(size, garbage));
  encode_revolution(sent, stream);
  StreamParser parser;
  std::vector<WireRevolution> got;
  feed_in_transfers(parser, stream, transfer, got);
  if (got.empty() || !same(got.back(), sent)) std::abort();
  return 0;
}
