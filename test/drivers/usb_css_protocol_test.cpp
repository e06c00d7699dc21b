#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "drivers/usb/css_protocol.hpp"
#include "drivers/usb/css_stream_parser.hpp"

namespace rangefit::drivers::css_usb {
namespace usb_css_protocol_test {

WireRevolution revolution(std::uint32_t sequence) {
  WireRevolution r;
  r.sequence = sequence;
  r.device_time_us = 4'000'000'000ull + sequence * 142'857ull;
  r.period_us = 142'857;
  r.flags = 3;
  for (std::size_t i = 0; i < kSamples; ++i) {
    r.samples[i] = {static_cast<std::uint16_t>(i % 7 == 0 ? kNoReturn : 1000 + i * 17 + sequence),
                    static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(255 - i % 256)};
  }
  return r;
}

std::vector<std::uint8_t> frames(std::uint32_t first, std::uint32_t count) {
  std::vector<std::uint8_t> out;
  for (std::uint32_t k = 0; k < count; ++k) encode_revolution(revolution(first + k), out);
  return out;
}

struct Collected {
  std::vector<std::uint32_t> sequences;
  std::vector<std::uint32_t> missing;
  std::vector<bool> discontinuity;
};

void feed(StreamParser& parser, std::span<const std::uint8_t> bytes, Collected& out) {
  parser.feed(bytes, [&](const StreamParser::Frame& f) {
    out.sequences.push_back(f.revolution.sequence);
    out.missing.push_back(f.missing_before);
    out.discontinuity.push_back(f.discontinuity);
    EXPECT_EQ(f.revolution.samples[5].range_um,
              revolution(f.revolution.sequence).samples[5].range_um);
  });
}

TEST(CssProtocol, Crc32MatchesTheStandardCheckValue) {
  const std::string check = "123456789";
  EXPECT_EQ(crc32({reinterpret_cast<const std::uint8_t*>(check.data()), check.size()}),
            0xCBF43926u);
  EXPECT_EQ(crc32({}), 0u);
}

TEST(CssProtocol, FrameRoundTripsAndHasTheDocumentedLayout) {
  std::vector<std::uint8_t> bytes;
  encode_revolution(revolution(42), bytes);
  ASSERT_EQ(bytes.size(), kFrameBytes);
  EXPECT_EQ(bytes.size(), 2076u);
  EXPECT_THAT(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 8),
              ::testing::ElementsAre('C', 'S', 'S', '1', 42, 0, 0, 0));
  EXPECT_EQ(bytes[20] | bytes[21] << 8, 512);
  const auto decoded = decode_revolution(bytes);
  ASSERT_TRUE(decoded);
  const WireRevolution expected = revolution(42);
  EXPECT_EQ(decoded->sequence, 42u);
  EXPECT_EQ(decoded->device_time_us, expected.device_time_us);
  EXPECT_EQ(decoded->period_us, expected.period_us);
  EXPECT_EQ(decoded->flags, 3u);
  for (std::size_t i = 0; i < kSamples; ++i) {
    EXPECT_EQ(decoded->samples[i].range_um, expected.samples[i].range_um);
    EXPECT_EQ(decoded->samples[i].quality, expected.samples[i].quality);
  }
  bytes[100] ^= 1;
  EXPECT_FALSE(decode_revolution(bytes));
  EXPECT_FALSE(decode_revolution(std::span(bytes).first(kFrameBytes - 1)));
}

TEST(CssProtocol, RangesConvertWithMicrometreResolution) {
  EXPECT_TRUE(std::isnan(range_mm(kNoReturn)));
  EXPECT_FLOAT_EQ(range_mm(0), 65.0f);
  EXPECT_FLOAT_EQ(range_mm(12345), 77.345f);
  EXPECT_EQ(range_um(77.345f), 12345);
  EXPECT_EQ(range_um(64.0f), kNoReturn);
  EXPECT_EQ(range_um(200.0f), kNoReturn);
  EXPECT_EQ(range_um(std::nanf("")), kNoReturn);
}

TEST(CssProtocol, InfoRoundTrips) {
  DeviceInfo info;
  info.serial = "OST-0042";
  info.firmware = 0x010203;
  const auto bytes = encode_info(info);
  const auto back = decode_info(bytes);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->serial, "OST-0042");
  EXPECT_EQ(back->firmware, 0x010203u);
  EXPECT_EQ(back->samples_per_revolution, 512);
  EXPECT_EQ(back->scan_diameter_um, 27000u);
  EXPECT_FALSE(decode_info(std::span(bytes).first(10)));
}

TEST(CssStreamParser, EmptyInputYieldsNothing) {
  StreamParser parser;
  Collected got;
  feed(parser, {}, got);
  EXPECT_TRUE(got.sequences.empty());
  EXPECT_EQ(parser.counters().resyncs, 0u);
}

TEST(CssStreamParser, FramesSplitAtEveryPossibleBoundaryAllArrive) {
  const auto bytes = frames(7, 3);
  for (std::size_t chunk : {1u, 3u, 64u, 512u, 2075u, 2077u, 5000u}) {
    StreamParser parser;
    Collected got;
    for (std::size_t i = 0; i < bytes.size(); i += chunk) {
      feed(parser, std::span(bytes).subspan(i, std::min(chunk, bytes.size() - i)), got);
    }
    EXPECT_THAT(got.sequences, ::testing::ElementsAre(7, 8, 9)) << "chunk " << chunk;
    EXPECT_EQ(parser.counters().resyncs, 0u);
    EXPECT_EQ(parser.counters().crc_errors, 0u);
  }
}

TEST(CssStreamParser, GarbageAndCorruptFramesAreSkippedAndCounted) {
  std::vector<std::uint8_t> bytes = {'x', 'C', 'S', 'S', 'y', 'C'};  // junk, a false start
  const auto good = frames(1, 4);
  bytes.insert(bytes.end(), good.begin(), good.end());
  bytes[6 + kFrameBytes + 500] ^= 0x40;  // frame 2 corrupt
  StreamParser parser;
  Collected got;
  feed(parser, bytes, got);
  EXPECT_THAT(got.sequences, ::testing::ElementsAre(1, 3, 4));
  EXPECT_THAT(got.missing, ::testing::ElementsAre(0, 1, 0));
  EXPECT_EQ(parser.counters().crc_errors, 1u);
  EXPECT_EQ(parser.counters().resyncs, 2u);
  EXPECT_EQ(parser.counters().gaps, 1u);
  EXPECT_EQ(parser.counters().frames, 3u);
}

TEST(CssStreamParser, SequenceWrapIsNotAGapButARestartIsADiscontinuity) {
  StreamParser parser;
  Collected got;
  feed(parser, frames(0xFFFFFFFEu, 2), got);  // ..FE, ..FF
  feed(parser, frames(0, 1), got);            // wraps to 0
  feed(parser, frames(5000000, 1), got);      // device restarted elsewhere
  EXPECT_THAT(got.discontinuity, ::testing::ElementsAre(true, false, false, true));
  EXPECT_EQ(parser.counters().gaps, 0u);
  EXPECT_EQ(parser.counters().discontinuities, 1u);
}

TEST(CssStreamParser, ResetDropsAPartialFrame) {
  const auto bytes = frames(1, 2);
  StreamParser parser;
  Collected got;
  feed(parser, std::span(bytes).first(1000), got);
  parser.reset();  // unplugged mid-transfer
  feed(parser, std::span(bytes).subspan(kFrameBytes), got);
  EXPECT_THAT(got.sequences, ::testing::ElementsAre(2));
  EXPECT_THAT(got.discontinuity, ::testing::ElementsAre(true));
}

TEST(CssStreamParser, RandomCorruptionNeverLosesAnIntactFrame) {
  std::mt19937 rng(8);
  const auto clean = frames(100, 50);
  std::vector<std::uint8_t> bytes = clean;
  std::vector<bool> damaged(50, false);
  for (int k = 0; k < 20; ++k) {
    const std::size_t at = std::uniform_int_distribution<std::size_t>(0, bytes.size() - 1)(rng);
    bytes[at] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    damaged[at / kFrameBytes] = true;
  }
  StreamParser parser;
  Collected got;
  for (std::size_t i = 0; i < bytes.size(); i += 777) {
    feed(parser, std::span(bytes).subspan(i, std::min<std::size_t>(777, bytes.size() - i)), got);
  }
  std::vector<std::uint32_t> intact;
  for (std::uint32_t k = 0; k < 50; ++k) {
    if (!damaged[k]) intact.push_back(100 + k);
  }
  EXPECT_EQ(got.sequences, intact);
  EXPECT_EQ(parser.counters().frames, intact.size());
  EXPECT_EQ(parser.counters().gaps, intact.back() - intact.front() + 1 - intact.size());
}

}  // namespace usb_css_protocol_test
}  // namespace rangefit::drivers::css_usb
