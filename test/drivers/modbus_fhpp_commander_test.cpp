// The host-side FHPP state machine on its own: edge handshakes and refusals, no transport.
#include <gtest/gtest.h>

#include "drivers/modbus/fhpp_commander.hpp"

namespace rangefit::drivers::fhpp {
namespace modbus_fhpp_commander_test {

constexpr std::uint8_t kReadyScon = kSconEnabled | kSconOpen | kSconLoadVoltage;
constexpr std::uint8_t kIdleSpos = kSposHalt | kSposMotionComplete | kSposReferenced;

Commander ready_commander() {
  Commander c(AxisScale{.increments_per_mm = 100.0, .max_speed_mm_s = 200.0});
  c.observe({kReadyScon, kIdleSpos, 0, 0, 0});
  return c;
}

TEST(FhppCommander, RefusesEveryRequestBeforeTheFirstStatus) {
  Commander c(AxisScale{});
  Commander::Ticket t;
  EXPECT_FALSE(c.request_enable(t).ok);
  EXPECT_FALSE(c.request_home(t).ok);
  EXPECT_FALSE(c.request_move(1.0, 1.0, 0.0, 10.0, t).ok);
  EXPECT_FALSE(c.request_halt(t).ok);
  EXPECT_FALSE(c.motion_complete());
  const OutputTelegram idle = c.next_output();
  EXPECT_EQ(idle.ccon, kCconModeDirect);  // not enabled, halt not active
  EXPECT_EQ(idle.cpos, kCposHalt);
}

TEST(FhppCommander, MoveRaisesStartUntilTheDriveAcknowledgesThenDropsIt) {
  Commander c = ready_commander();
  Commander::Ticket t;
  ASSERT_TRUE(c.request_move(12.5, 100.0, 0.0, 50.0, t).ok);
  EXPECT_FALSE(c.accepted(t));
  OutputTelegram out = c.next_output();
  EXPECT_TRUE(out.cpos & kCposStart);
  EXPECT_EQ(out.position_inc, 1250);
  EXPECT_EQ(out.velocity_pct, 50);
  c.observe({kReadyScon, kSposHalt | kSposReferenced, 0, 0, 0});  // no ACK yet: keep START high
  EXPECT_TRUE(c.next_output().cpos & kCposStart);
  c.observe({kReadyScon, kSposHalt | kSposAck | kSposMoving | kSposReferenced, 0, 50, 10});
  EXPECT_TRUE(c.accepted(t));
  EXPECT_FALSE(c.next_output().cpos & kCposStart);
  EXPECT_FALSE(c.motion_complete());
  c.observe({kReadyScon, kIdleSpos, 0, 0, 1250});
  EXPECT_TRUE(c.motion_complete());
}

TEST(FhppCommander, WaitsForAckToDropBeforeRaisingTheNextStart) {
  Commander c = ready_commander();
  c.observe({kReadyScon, kIdleSpos | kSposAck, 0, 0, 0});  // ACK of an earlier command still high
  Commander::Ticket t;
  ASSERT_TRUE(c.request_move(5.0, 10.0, 0.0, 50.0, t).ok);
  EXPECT_FALSE(c.next_output().cpos & kCposStart);
  c.observe({kReadyScon, kIdleSpos, 0, 0, 0});
  EXPECT_TRUE(c.next_output().cpos & kCposStart);
}

TEST(FhppCommander, RefusesMotionInFaultWithTheStatusBitsButAllowsHaltAndReset) {
  Commander c = ready_commander();
  c.observe({kSconFault | kSconLoadVoltage, kIdleSpos, 0, 0, 0});
  Commander::Ticket t;
  const hal::Status s = c.request_move(5.0, 10.0, 0.0, 50.0, t);
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.message.find("FAULT"), std::string::npos);
  EXPECT_NE(s.message.find("SCON=0x18 [FAULT VLOAD]"), std::string::npos) << s.message;
  EXPECT_FALSE(c.request_enable(t).ok);
  EXPECT_TRUE(c.request_halt(t).ok);
  EXPECT_FALSE(c.next_output().cpos & kCposHalt);  // halt active
  ASSERT_TRUE(c.request_reset(t).ok);
  int raised = 0;
  for (int i = 0; i < 10; ++i) raised += (c.next_output().ccon & kCconReset) ? 1 : 0;
  EXPECT_EQ(raised, Commander::kResetCycles);
  c.observe({kSconLoadVoltage, kIdleSpos, 0, 0, 0});
  EXPECT_TRUE(c.accepted(t));
}

TEST(FhppCommander, RefusesMovesOutsideTravelWithoutSpeedOrReference) {
  Commander c = ready_commander();
  Commander::Ticket t;
  EXPECT_FALSE(c.request_move(60.0, 10.0, 0.0, 50.0, t).ok);
  EXPECT_FALSE(c.request_move(5.0, 0.0, 0.0, 50.0, t).ok);
  c.observe({kReadyScon, kSposHalt | kSposMotionComplete, 0, 0, 0});  // REF lost
  const hal::Status s = c.request_move(5.0, 10.0, 0.0, 50.0, t);
  EXPECT_NE(s.message.find("not referenced"), std::string::npos);
  c.observe({kReadyScon | kSconFctMmi, kIdleSpos, 0, 0, 0});
  EXPECT_NE(c.request_home(t).message.find("another master"), std::string::npos);
}

}  // namespace modbus_fhpp_commander_test
}  // namespace rangefit::drivers::fhpp
