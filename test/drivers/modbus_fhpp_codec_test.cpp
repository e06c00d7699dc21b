#include <gtest/gtest.h>

#include <vector>

#include "drivers/modbus/fhpp_codec.hpp"
#include "drivers/modbus/position_check.hpp"

namespace rangefit::drivers::fhpp {
namespace modbus_fhpp_codec_test {

TEST(FhppCodec, OutputTelegramMapsBytesLowByteFirstIntoRegisters) {
  OutputTelegram t{0x43, 0x03, 0x00, 50, 0x12345678};
  const Registers r = encode(t, ByteOrder::kLowByteFirst);
  // Register k = byte 2k | byte 2k+1 << 8: CCON low, CPOS high; position low word first.
  EXPECT_EQ(r[0], 0x0343);
  EXPECT_EQ(r[1], 50 << 8);
  EXPECT_EQ(r[2], 0x5678);
  EXPECT_EQ(r[3], 0x1234);
}

TEST(FhppCodec, InputTelegramRoundTripsInBothByteOrders) {
  const InputTelegram t{kSconEnabled | kSconOpen, kSposReferenced | kSposMotionComplete, 0, 7,
                        -123456};
  for (ByteOrder order : {ByteOrder::kLowByteFirst, ByteOrder::kHighByteFirst}) {
    const Registers r = encode(t, order);
    const auto back = decode_input(r, order);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, t);
  }
}

TEST(FhppCodec, WrongByteOrderGivesADifferentPosition) {
  const InputTelegram t{0, 0, 0, 0, 250000};  // 250 mm at 1000 inc/mm
  const auto wrong = decode_input(encode(t, ByteOrder::kLowByteFirst), ByteOrder::kHighByteFirst);
  ASSERT_TRUE(wrong.has_value());
  EXPECT_NE(wrong->position_inc, t.position_inc);
}

TEST(FhppCodec, ShortOrEmptyRegisterSpanIsRejected) {
  EXPECT_FALSE(decode_input({}, ByteOrder::kLowByteFirst).has_value());
  const std::vector<std::uint16_t> three{1, 2, 3};
  EXPECT_FALSE(decode_output(three, ByteOrder::kLowByteFirst).has_value());
}

TEST(FhppCodec, ScaleConvertsIncrementsAndSpeedPercent) {
  AxisScale s{.increments_per_mm = 100.0, .max_speed_mm_s = 200.0};
  EXPECT_EQ(s.to_increments(12.345), 1235);
  EXPECT_DOUBLE_EQ(s.to_mm(-250), -2.5);
  EXPECT_EQ(s.to_increments(1e12), 2147483647);
  EXPECT_EQ(s.mm_s_to_pct(50.0), 25);
  EXPECT_EQ(s.mm_s_to_pct(0.1), 1);
  EXPECT_EQ(s.mm_s_to_pct(1000.0), 100);
  EXPECT_EQ(s.mm_s_to_pct(-3.0), 0);
  EXPECT_DOUBLE_EQ(s.pct_to_mm_s(25), 50.0);
}

TEST(FhppCodec, StatusDescriptionNamesTheSetBits) {
  const std::string d = describe_status(kSconEnabled | kSconFault, kSposHalt | kSposReferenced);
  EXPECT_EQ(d, "SCON=0x09 [ENABLED FAULT] SPOS=0x81 [HALT REF]");
  EXPECT_EQ(describe_status(0, 0), "SCON=0x00 [] SPOS=0x00 []");
}

TEST(PositionCheck, FlagsPositionsOutsideTravelAndImpossibleJumps) {
  const PositionCheckConfig c{.min_mm = 0, .max_mm = 500, .margin_mm = 2, .max_speed_mm_s = 100};
  using std::chrono::milliseconds;
  EXPECT_EQ(check_position(c, 250.0, hal::Timestamp{}, std::nullopt), "");
  EXPECT_NE(check_position(c, 9000.0, hal::Timestamp{}, std::nullopt).find("byte order"),
            std::string::npos);
  const PositionReference prev{100.0, hal::Timestamp{milliseconds(0)}};
  EXPECT_EQ(check_position(c, 101.0, hal::Timestamp{milliseconds(10)}, prev), "");
  EXPECT_NE(check_position(c, 150.0, hal::Timestamp{milliseconds(10)}, prev).find("jump"),
            std::string::npos);
}

}  // namespace modbus_fhpp_codec_test
}  // namespace rangefit::drivers::fhpp
