// One test per Modbus fault kind (PROTOCOLS.md, "Faults each driver must survive"): the fault is
// injected by the loopback proxy or the simulated drive, and each test checks that the driver
// detects it, reports a clear reason, and recovers without a restart.
#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include <cmath>

#include "test/drivers/modbus_test_rig.hpp"

namespace rangefit::test {
namespace modbus_fault_test {

// Every valid sample must match the truth at its stamp: a reply taken for the answer to a later
// request would place an old position at a new stamp and break this while the axis moves.
void expect_samples_follow_truth(const ModbusRig& rig, const std::vector<hal::AxisSample>& samples,
                                 double speed_mm_s) {
  std::size_t valid = 0;
  for (const auto& s : samples) {
    if (!s.valid) continue;
    ++valid;
    const double tol = speed_mm_s * std::chrono::duration<double>(s.uncertainty).count() / 2 + 2e-3;
    EXPECT_NEAR(s.position_mm, rig.drive.position_at(s.stamp), tol)
        << "stamp " << s.stamp.count() << " uncertainty " << s.uncertainty.count() << " ns";
  }
  EXPECT_GT(valid, 0u);
}

TEST(FhppAxisFaults, ConnectionRefusedIsRetriedUntilTheDeviceListens) {
  ModbusRig rig(true);
  rig.proxy->set_listening(false);
  rig.make_axis();
  ASSERT_TRUE(rig.axis->start().ok);
  ASSERT_TRUE(wait_until([&] { return any_event_contains(*rig.axis, "Connection refused"); }, 2s))
      << joined_events(*rig.axis);
  EXPECT_EQ(rig.axis->health().state, hal::DeviceState::kDisconnected);
  EXPECT_FALSE(rig.axis->enable().ok);
  rig.proxy->set_listening(true);
  EXPECT_TRUE(rig.polls_again()) << joined_events(*rig.axis);
  EXPECT_TRUE(rig.axis->health().message.empty());
}

TEST(FhppAxisFaults, ConnectAttemptsBackOffExponentiallyUpToTheCap) {
  ModbusRig rig(true);
  rig.proxy->set_listening(false);
  rig.make_axis();  // 5 ms period; back-off 5 ms doubling to 80 ms
  ASSERT_TRUE(rig.axis->start().ok);
  std::this_thread::sleep_for(400ms);
  // Without back-off 400 ms would be 80 attempts; with it they start at 0, 5, 10, 20, 40, 80,
  // 160, 240, 320 and 400 ms.
  const auto attempts = rig.axis->stats().connect_attempts;
  EXPECT_GE(attempts, 4u);
  EXPECT_LE(attempts, 14u);  // 10 on an idle machine
  rig.proxy->set_listening(true);
  EXPECT_TRUE(rig.polls_again());  // at most one cap (80 ms) later
}

TEST(FhppAxisFaults, AWrongUnitIdIsAConfigurationError) {
  ModbusRig rig(false);
  rig.config.link.unit_id = 7;  // the drive is unit 1
  rig.make_axis();
  ASSERT_TRUE(rig.axis->start().ok);
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().state == hal::DeviceState::kFault; }, 2s));
  EXPECT_NE(rig.axis->health().message.find("configuration error: exception 11"), std::string::npos)
      << rig.axis->health().message;
  EXPECT_NE(rig.axis->health().message.find("from unit 7"), std::string::npos);
  EXPECT_EQ(rig.axis->health().counters.reconnects, 0u);
}

TEST(FhppAxisFaults, LateRepliesAreNeverTakenForLaterOnes) {
  ModbusRig rig(true);
  rig.start_streaming();
  rig.enable_and_home();
  std::vector<hal::AxisSample> samples;
  rig.axis->read(samples, 0ms);  // homing ran at another speed
  samples.clear();
  ASSERT_TRUE(rig.axis->move_to(400.0, 250.0).ok);
  // Replies arrive 150 ms late, after the 100 ms response timeout.
  rig.proxy->set_reply_delay(150ms);
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().counters.timeouts >= 2; }, 2s));
  rig.proxy->set_reply_delay(0ms);
  EXPECT_TRUE(rig.polls_again(20)) << joined_events(*rig.axis);
  EXPECT_TRUE(any_event_contains(*rig.axis, "within the response timeout (100 ms); reconnecting"))
      << joined_events(*rig.axis);
  EXPECT_GE(rig.axis->health().counters.reconnects, 2u);
  rig.axis->read(samples, 0ms);
  expect_samples_follow_truth(rig, samples, 250.0);
}

TEST(FhppAxisFaults, ADroppedRequestTimesOutAndPollingResumes) {
  ModbusRig rig(true);
  rig.start_streaming();
  rig.proxy->drop_next_request();
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().counters.timeouts >= 1; }, 2s));
  EXPECT_TRUE(rig.polls_again());
  EXPECT_TRUE(any_event_contains(*rig.axis, "no reply"));
}

TEST(FhppAxisFaults, AResetMidRequestReconnects) {
  ModbusRig rig(true);
  rig.start_streaming();
  rig.proxy->reset_next_request();
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().counters.reconnects >= 1; }, 2s))
      << joined_events(*rig.axis);
  EXPECT_TRUE(rig.polls_again());
  EXPECT_TRUE(any_event_contains(*rig.axis, "lost mid-request")) << joined_events(*rig.axis);
  EXPECT_EQ(rig.proxy->resets(), 1u);
}

TEST(FhppAxisFaults, AHalfOpenConnectionIsDetectedAndReplaced) {
  ModbusRig rig(true);
  rig.start_streaming();
  rig.proxy->set_black_hole(true);  // nothing flows, nothing is closed
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().counters.timeouts >= 2; }, 2s));
  EXPECT_EQ(rig.axis->health().state, hal::DeviceState::kDisconnected);
  rig.proxy->set_black_hole(false);
  EXPECT_TRUE(rig.polls_again()) << joined_events(*rig.axis);
  EXPECT_GE(rig.axis->health().counters.reconnects, 1u);
  EXPECT_FALSE(rig.drive.fault());  // shorter than the drive's connection timeout
}

TEST(FhppAxisFaults, TheDrivesConnectionTimeoutFaultIsNamedAndAcknowledged) {
  ModbusRig rig(true);
  rig.start_streaming();
  rig.enable_and_home();
  rig.proxy->set_black_hole(true);
  ASSERT_TRUE(wait_until([&] { return rig.drive.fault(); }, 2s));  // 600 ms without a request
  EXPECT_NE(rig.drive.fault_reason().find("connection timeout"), std::string::npos);
  rig.proxy->set_black_hole(false);
  ASSERT_TRUE(wait_until([&] { return rig.axis->stats().comm_timeout_faults == 1; }, 2s))
      << joined_events(*rig.axis);
  EXPECT_TRUE(rig.polls_again()) << joined_events(*rig.axis);
  EXPECT_TRUE(any_event_contains(*rig.axis, "drive FAULT: connection timeout"))
      << joined_events(*rig.axis);
  EXPECT_FALSE(rig.drive.fault());
  ASSERT_TRUE(rig.axis->enable().ok) << rig.axis->health().message;
  EXPECT_TRUE(rig.axis->move_to(20.0, 500.0).ok) << rig.axis->health().message;
}

TEST(FhppAxisFaults, ADriveFaultRefusesMotionUntilReset) {
  ModbusRig rig(false);
  rig.start_streaming();
  rig.enable_and_home();
  rig.drive.inject_fault(hal::monotonic_now(), "following error");
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().state == hal::DeviceState::kFault; }, 2s));
  EXPECT_NE(rig.axis->health().message.find("drive FAULT; SCON="), std::string::npos)
      << rig.axis->health().message;
  const hal::Status refused = rig.axis->move_to(200.0, 100.0);
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.message.find("FAULT"), std::string::npos) << refused.message;
  EXPECT_NE(refused.message.find("SPOS="), std::string::npos) << refused.message;
  EXPECT_FALSE(rig.axis->enable().ok);
  ASSERT_TRUE(rig.axis->reset_fault().ok) << rig.axis->health().message;
  EXPECT_TRUE(rig.polls_again());
  ASSERT_TRUE(rig.axis->enable().ok) << rig.axis->health().message;
  EXPECT_TRUE(rig.axis->move_to(200.0, 500.0).ok) << rig.axis->health().message;
  EXPECT_EQ(rig.axis->health().counters.faults, 1u);
}

TEST(FhppAxisFaults, AnIllegalAddressExceptionIsAConfigurationErrorNotAReconnect) {
  ModbusRig rig(false);
  rig.start_streaming();
  rig.server.set_exception(MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().state == hal::DeviceState::kFault; }, 2s));
  const std::string msg = rig.axis->health().message;
  EXPECT_NE(msg.find("configuration error: exception 2 (Illegal data address)"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("not reconnecting"), std::string::npos);
  EXPECT_FALSE(rig.axis->enable().ok);
  rig.server.set_exception(0);
  EXPECT_TRUE(rig.polls_again());
  EXPECT_EQ(rig.axis->health().counters.reconnects, 0u);
  EXPECT_EQ(rig.server.connections(), 1);
}

TEST(FhppAxisFaults, ABusyExceptionIsRetriedWithoutAFault) {
  ModbusRig rig(false);
  rig.start_streaming();
  rig.server.set_exception(MODBUS_EXCEPTION_SLAVE_OR_SERVER_BUSY);
  ASSERT_TRUE(wait_until([&] { return rig.axis->stats().exceptions >= 3; }, 2s));
  EXPECT_NE(rig.axis->health().state, hal::DeviceState::kFault);
  EXPECT_TRUE(any_event_contains(*rig.axis, "drive busy")) << joined_events(*rig.axis);
  rig.server.set_exception(0);
  EXPECT_TRUE(rig.polls_again());
  EXPECT_EQ(rig.axis->health().counters.reconnects, 0u);
}

TEST(FhppAxisFaults, PositionsWithTheWrongByteOrderAreMarkedImplausible) {
  ModbusRig rig(false);
  rig.start_streaming();
  rig.server.set_byte_order(drivers::fhpp::ByteOrder::kHighByteFirst);
  ASSERT_TRUE(wait_until([&] { return rig.axis->stats().implausible >= 3; }, 2s));
  EXPECT_TRUE(any_event_contains(*rig.axis, "check byte order")) << joined_events(*rig.axis);
  EXPECT_FALSE(rig.axis->latest()->valid);
  rig.server.set_byte_order(drivers::fhpp::ByteOrder::kLowByteFirst);
  ASSERT_TRUE(wait_until([&] { return rig.axis->latest()->valid; }, 2s));
  EXPECT_NEAR(rig.axis->latest()->position_mm, 100.0, 1e-3);
  EXPECT_TRUE(rig.axis->health().message.empty()) << rig.axis->health().message;
}

TEST(FhppAxisFaults, SamplesWithATooLongRoundTripAreMarkedInvalid) {
  ModbusRig rig(true);
  rig.start_streaming();
  rig.proxy->set_reply_delay(50ms);  // over the 30 ms limit, under the 100 ms timeout
  ASSERT_TRUE(wait_until([&] { return rig.axis->stats().late_round_trips >= 3; }, 2s));
  EXPECT_FALSE(rig.axis->latest()->valid);
  EXPECT_GT(rig.axis->latest()->uncertainty, rig.config.max_round_trip);
  rig.proxy->set_reply_delay(0ms);
  EXPECT_TRUE(wait_until([&] { return rig.axis->latest()->valid; }, 2s));
}

TEST(FhppAxisFaults, AnotherClientTakingControlIsReportedAndControlReturnsWhenItLeaves) {
  ModbusRig rig(false);
  rig.start_streaming();
  rig.enable_and_home();
  modbus_t* other = modbus_new_tcp("127.0.0.1", rig.server.port());
  ASSERT_EQ(modbus_connect(other), 0);
  const auto out =
      drivers::fhpp::encode(drivers::fhpp::OutputTelegram{drivers::fhpp::kCconEnable, 0, 0, 0, 0},
                            drivers::fhpp::ByteOrder::kLowByteFirst);
  std::uint16_t in[4];
  ASSERT_EQ(modbus_write_and_read_registers(other, 0, 4, out.data(), 0, 4, in), 4);
  ASSERT_TRUE(wait_until([&] { return rig.axis->stats().takeovers == 1; }, 2s));
  EXPECT_EQ(rig.axis->health().state, hal::DeviceState::kFault);
  EXPECT_NE(rig.axis->health().message.find("another master"), std::string::npos);
  const hal::Status refused = rig.axis->move_to(200.0, 100.0);
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.message.find("FCT/MMI"), std::string::npos) << refused.message;
  modbus_close(other);
  modbus_free(other);
  EXPECT_TRUE(rig.polls_again()) << joined_events(*rig.axis);
  EXPECT_TRUE(rig.axis->move_to(200.0, 500.0).ok) << rig.axis->health().message;
}

}  // namespace modbus_fault_test
}  // namespace rangefit::test
