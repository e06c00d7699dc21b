// CAN codecs: CiA 402, PowerCube and the ranger's CAN FD profile, encode/decode without transport.
#include <gtest/gtest.h>

#include <array>
#include <string_view>

#include "drivers/can/cia402_codec.hpp"
#include "drivers/common/crc32.hpp"
#include "drivers/can/powercube_codec.hpp"
#include "drivers/can/ranger_codec.hpp"

namespace rangefit::drivers::can {
namespace can_codec_test {

TEST(CanFrame, FdLengthsPadToTheNextValidSize) {
  EXPECT_EQ(fd_padded_length(0), 0);
  EXPECT_EQ(fd_padded_length(8), 8);
  EXPECT_EQ(fd_padded_length(9), 12);
  EXPECT_EQ(fd_padded_length(25), 32);
  EXPECT_EQ(fd_padded_length(49), 64);
  EXPECT_TRUE(valid_fd_length(48));
  EXPECT_FALSE(valid_fd_length(50));
}

TEST(Crc32, MatchesTheStandardCheckValue) {
  constexpr std::string_view kCheck = "123456789";
  const std::span bytes(reinterpret_cast<const std::uint8_t*>(kCheck.data()), kCheck.size());
  EXPECT_EQ(crc32(bytes), 0xCBF43926u);
  EXPECT_EQ(crc32({}), 0u);
}

TEST(Cia402Codec, EmptyFramesAreBadLengthsOrUnknown) {
  EXPECT_EQ(cia402::decode(CanFrame{}).kind, cia402::Kind::kBadLength);  // NMT needs 2 bytes
  EXPECT_EQ(cia402::decode(make_frame(0x7FF, {})).kind, cia402::Kind::kUnknown);
  EXPECT_EQ(cia402::decode(make_frame(0x400, {})).kind, cia402::Kind::kUnknown);
  EXPECT_EQ(cia402::decode(make_frame(0x081, {})).kind, cia402::Kind::kBadLength);  // EMCY
}

TEST(Cia402Codec, Tpdo1CarriesStatuswordAndSignedPosition) {
  const cia402::Message m = cia402::decode(cia402::encode_tpdo1(5, 0x0637, -123456));
  EXPECT_EQ(m.kind, cia402::Kind::kTpdo1);
  EXPECT_EQ(m.node, 5);
  EXPECT_EQ(m.statusword, 0x0637);
  EXPECT_EQ(m.position, -123456);
}

TEST(Cia402Codec, WrongLengthsAreReportedNotDecoded) {
  CanFrame f = cia402::encode_tpdo1(5, 0x0637, 1);
  f.len = 4;
  EXPECT_EQ(cia402::decode(f).kind, cia402::Kind::kBadLength);
  const std::array<std::uint8_t, 3> two_bytes_heartbeat{5, 0, 0};
  EXPECT_EQ(cia402::decode(make_frame(0x705, two_bytes_heartbeat)).kind, cia402::Kind::kBadLength);
}

TEST(Cia402Codec, SyncCounterRoundTripsAndWraps) {
  EXPECT_EQ(cia402::decode(cia402::encode_sync(17)).sync_counter, 17);
  EXPECT_EQ(cia402::encode_sync(0).len, 0);
  EXPECT_EQ(cia402::next_sync_counter(240, 240), 1);
  EXPECT_EQ(cia402::next_sync_counter(7, 240), 8);
}

TEST(Cia402Codec, HeartbeatEmcyAndNmtDecode) {
  const auto hb = cia402::decode(cia402::encode_heartbeat(9, cia402::kBootUp));
  EXPECT_EQ(hb.kind, cia402::Kind::kHeartbeat);
  EXPECT_EQ(hb.node, 9);
  EXPECT_EQ(hb.nmt_state, cia402::kBootUp);
  const auto emcy = cia402::decode(cia402::encode_emcy(9, 0x8611, 0x81));
  EXPECT_EQ(emcy.kind, cia402::Kind::kEmcy);
  EXPECT_EQ(emcy.emcy_code, 0x8611);
  const auto nmt = cia402::decode(cia402::encode_nmt(cia402::kNmtStart, 0));
  EXPECT_EQ(nmt.kind, cia402::Kind::kNmt);
  EXPECT_EQ(nmt.nmt_command, cia402::kNmtStart);
}

TEST(Cia402Codec, ExpeditedSdoDownloadSetsSizeBits) {
  const CanFrame f = cia402::encode_sdo_download(3, 0x1017, 0, 100, 2);
  EXPECT_EQ(f.id, 0x603u);
  EXPECT_EQ(f.data[0], 0x2B);  // expedited, size indicated, 2 bytes
  const auto m = cia402::decode(f);
  EXPECT_EQ(m.kind, cia402::Kind::kSdoRequest);
  EXPECT_EQ(m.sdo_index, 0x1017);
  EXPECT_EQ(m.sdo_data, 100u);
  EXPECT_TRUE(cia402::sdo_is_download_request(m.sdo_command));
}

TEST(PowerCubeCodec, PositionReplyRoundTripsFloatAndState) {
  powercube::PositionReply r{7, -1.25F, powercube::kStateMoving, 0x3};
  const CanFrame f = powercube::encode_position_reply(r);
  EXPECT_EQ(f.id, 0x0A7u);
  const auto m = powercube::decode(f);
  ASSERT_EQ(m.kind, powercube::Kind::kPositionReply);
  EXPECT_FLOAT_EQ(m.reply.position_rad, -1.25F);
  EXPECT_EQ(m.reply.state, powercube::kStateMoving);
  EXPECT_EQ(powercube::decode(powercube::encode_position_request(7)).kind,
            powercube::Kind::kPositionRequest);
}

TEST(PowerCubeCodec, ShortReplyAndForeignIdsAreRejected) {
  CanFrame f = powercube::encode_position_reply({7, 1.0F, 0, 0});
  f.len = 6;
  EXPECT_EQ(powercube::decode(f).kind, powercube::Kind::kBadLength);
  EXPECT_EQ(powercube::decode(make_frame(0x181, {})).kind, powercube::Kind::kOther);
  EXPECT_EQ(powercube::decode(CanFrame{}).kind, powercube::Kind::kOther);
}

class RangerCodec : public ::testing::Test {
 protected:
  void SetUp() override {
    p_.sequence = 41;
    p_.device_time_us = 0xFFFF'FF00u;
    p_.exposure_us = 300;
    p_.point_count = 512;
    p_.units_um = 4;
    p_.flags = ranger::kWireSaturated;
    for (std::size_t k = 0; k < 512; ++k) p_.range[k] = static_cast<std::uint16_t>(k * 7);
    p_.range[100] = ranger::kNoReturn;
    n_ = ranger::encode(0x20, p_, frames_);
  }
  // Feeds frames in the given order with increasing stamps; returns the last result.
  ranger::FeedResult feed_all(ranger::Reassembler& r, std::span<const std::size_t> order) {
    ranger::FeedResult last = ranger::FeedResult::kPending;
    for (std::size_t i : order) {
      CanFrame f = frames_[i];
      f.stamp = hal::Timestamp{std::chrono::microseconds(i)};
      last = r.feed(f);
    }
    return last;
  }
  ranger::WireProfile p_;
  std::array<CanFrame, ranger::kMaxSegments + 1> frames_{};
  std::size_t n_ = 0;
};

TEST_F(RangerCodec, A512PointProfileIsAHeaderAnd17PaddedFdFrames) {
  ASSERT_EQ(n_, 18u);
  EXPECT_EQ(frames_[0].len, 32);   // 25 header bytes padded
  EXPECT_EQ(frames_[1].len, 64);   // 2 + 31 * 2
  EXPECT_EQ(frames_[17].len, 48);  // 2 + 16 * 2 padded
  for (std::size_t i = 0; i < n_; ++i) {
    EXPECT_TRUE(frames_[i].is_fd());
    EXPECT_EQ(frames_[i].id, 0x3A0u);
    EXPECT_EQ(frames_[i].data[1], i);
  }
}

TEST_F(RangerCodec, EmptyProfileEncodesToNothing) {
  ranger::WireProfile empty;
  EXPECT_EQ(ranger::encode(1, empty, frames_), 0u);
}

TEST_F(RangerCodec, ReassemblesInAnyOrderWithIdenticalContent) {
  std::array<std::size_t, 18> order{};
  for (std::size_t i = 0; i < 18; ++i) order[i] = 17 - i;  // header last
  ranger::Reassembler r;
  ASSERT_EQ(feed_all(r, order), ranger::FeedResult::kComplete);
  EXPECT_EQ(r.profile().sequence, 41u);
  EXPECT_EQ(r.profile().device_time_us, 0xFFFF'FF00u);
  EXPECT_EQ(r.profile().flags, ranger::kWireSaturated);
  EXPECT_EQ(r.profile().range, p_.range);
  EXPECT_EQ(r.counters().complete, 1u);
}

TEST_F(RangerCodec, CorruptRangeDataFailsTheCrc) {
  frames_[5].data[10] ^= 0x01;
  std::array<std::size_t, 18> order{};
  for (std::size_t i = 0; i < 18; ++i) order[i] = i;
  ranger::Reassembler r;
  EXPECT_EQ(feed_all(r, order), ranger::FeedResult::kCrcError);
  EXPECT_EQ(r.counters().crc_errors, 1u);
}

TEST_F(RangerCodec, MissingSegmentTimesOutOrIsSupersededByTheNextProfile) {
  std::array<std::size_t, 17> order{};
  for (std::size_t i = 0, k = 0; i < 18; ++i)
    if (i != 9) order[k++] = i;
  ranger::Reassembler r(std::chrono::milliseconds(50));
  EXPECT_EQ(feed_all(r, order), ranger::FeedResult::kPending);
  EXPECT_FALSE(r.expire(hal::Timestamp{std::chrono::milliseconds(10)}));
  EXPECT_TRUE(r.expire(hal::Timestamp{std::chrono::milliseconds(60)}));
  EXPECT_EQ(r.counters().incomplete, 1u);
  // Superseded: the next profile's first frame abandons the incomplete one.
  EXPECT_EQ(feed_all(r, order), ranger::FeedResult::kPending);
  p_.sequence = 42;
  ranger::encode(0x20, p_, frames_);
  std::array<std::size_t, 18> all{};
  for (std::size_t i = 0; i < 18; ++i) all[i] = i;
  EXPECT_EQ(feed_all(r, all), ranger::FeedResult::kComplete);
  EXPECT_EQ(r.counters().incomplete, 2u);
}

TEST_F(RangerCodec, DuplicateSegmentsAndBadHeadersAreCounted) {
  ranger::Reassembler r;
  std::array<std::size_t, 3> dup{0, 1, 1};
  EXPECT_EQ(feed_all(r, dup), ranger::FeedResult::kDuplicate);
  CanFrame bad = frames_[0];
  bad.data[0] = 99;            // new profile sequence
  put_u16(bad.data, 12, 600);  // more points than the profile can hold
  EXPECT_EQ(r.feed(bad), ranger::FeedResult::kBadFrame);
  CanFrame tiny = frames_[3];
  tiny.len = 1;
  EXPECT_EQ(r.feed(tiny), ranger::FeedResult::kBadFrame);
  EXPECT_EQ(r.counters().duplicates, 1u);
  EXPECT_EQ(r.counters().bad_frames, 2u);
}

}  // namespace can_codec_test
}  // namespace rangefit::drivers::can
