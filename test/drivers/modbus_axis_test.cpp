// The FHPP driver against the simulated drive on Modbus TCP: stamping, the command state machine,
// function-code fallback, and a stripe-cell-like scan that must follow the simulated truth.
#include <gtest/gtest.h>

#include <cmath>

#include "test/drivers/modbus_test_rig.hpp"

namespace rangefit::test {
namespace modbus_axis_test {

// |measured - truth| allowed for a sample: the stamp is within +-uncertainty/2 of the instant the
// position was sampled, so at speed v the position can be off by v*uncertainty/2, plus one
// increment of quantisation.
double allowed_error_mm(const hal::AxisSample& s, double speed_mm_s) {
  return speed_mm_s * std::chrono::duration<double>(s.uncertainty).count() / 2.0 + 1e-3 + 1e-6;
}

TEST(FhppAxis, ReadsNothingAndRefusesCommandsBeforeStart) {
  drivers::FhppAxis axis(fast_axis_config(1));
  std::vector<hal::AxisSample> out;
  EXPECT_EQ(axis.read(out, 1ms), 0u);
  EXPECT_TRUE(out.empty());
  const hal::Status s = axis.enable();
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.message.find("not started"), std::string::npos);
  EXPECT_FALSE(axis.motion_complete());
}

TEST(FhppAxis, RejectsAPollPeriodAboveHalfTheDriveTimeout) {
  auto c = fast_axis_config(1);
  c.poll_period = 200ms;
  c.drive_comm_timeout = 300ms;
  drivers::FhppAxis axis(c);
  const hal::Status s = axis.start();
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.message.find("connection timeout"), std::string::npos);
}

TEST(FhppAxis, StampsEachPositionAtTheRoundTripMidpoint) {
  ModbusRig rig(false);
  rig.start_streaming();
  std::vector<hal::AxisSample> samples;
  ASSERT_TRUE(wait_until([&] { return rig.axis->read(samples, 10ms), samples.size() >= 10; }, 2s));
  for (const auto& s : samples) {
    EXPECT_EQ(s.valid, s.uncertainty <= rig.config.max_round_trip);
    EXPECT_GT(s.uncertainty.count(), 0);
    EXPECT_NEAR(s.position_mm, rig.drive.position_at(s.stamp), allowed_error_mm(s, 0.0));
  }
  for (std::size_t i = 1; i < samples.size(); ++i)
    EXPECT_GT(samples[i].stamp, samples[i - 1].stamp);
}

TEST(FhppAxis, RefusesToMoveBeforeHomingAndNamesTheStatusBits) {
  ModbusRig rig(false);
  rig.start_streaming();
  ASSERT_TRUE(rig.axis->enable().ok) << rig.axis->health().message;
  const hal::Status s = rig.axis->move_to(200.0, 100.0);
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.message.find("not referenced"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("SPOS="), std::string::npos) << s.message;
}

TEST(FhppAxis, RefusesATargetOutsideTheTravel) {
  ModbusRig rig(false);
  rig.start_streaming();
  rig.enable_and_home();
  const hal::Status s = rig.axis->move_to(900.0, 100.0);
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.message.find("outside travel"), std::string::npos) << s.message;
}

// Thesis 5.2.1: the axis carries the object through the stripe sensor's plane at scan speed; each
// profile is placed at the axis position of its exposure, so the samples must follow the truth.
TEST(FhppAxis, ScanMotionFollowsTheSimulatedTruthWithinTheRoundTripUncertainty) {
  ModbusRig rig(false);
  rig.start_streaming();
  rig.enable_and_home();
  EXPECT_NEAR(rig.axis->latest()->position_mm, 0.0, 1e-3);
  ASSERT_TRUE(rig.axis->move_to(50.0, 500.0).ok);
  ASSERT_TRUE(wait_until([&] { return rig.axis->motion_complete(); }, 2s));
  std::vector<hal::AxisSample> samples;
  rig.axis->read(samples, 0ms);
  samples.clear();
  const double scan_speed = 250.0;  // 50 % of the drive's top speed
  ASSERT_TRUE(rig.axis->move_to(150.0, scan_speed).ok);
  ASSERT_TRUE(wait_until([&] { return rig.axis->motion_complete(); }, 2s));
  ASSERT_TRUE(rig.axis->halt().ok);
  rig.axis->read(samples, 10ms);

  ASSERT_GE(samples.size(), 40u);  // 0.4 s of scan at a 5 ms period
  std::size_t moving = 0;
  for (const auto& s : samples) {
    if (!s.valid) continue;  // round trip over the limit (a loaded machine): not for fusion
    EXPECT_NEAR(s.position_mm, rig.drive.position_at(s.stamp), allowed_error_mm(s, scan_speed));
    if (s.position_mm > 51.0 && s.position_mm < 149.0) ++moving;
  }
  EXPECT_GE(moving, 30u);  // valid samples all along the scan
  EXPECT_NEAR(samples.back().position_mm, 150.0, 1e-3);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    EXPECT_GE(samples[i].position_mm, samples[i - 1].position_mm);  // never steps back
  }
}

TEST(FhppAxis, FallsBackToSeparateWriteAndReadWhenTheDeviceLacks0x17) {
  sim::SimAxisServerConfig server;
  server.supports_read_write = false;
  ModbusRig rig(false, server);
  rig.config.link.functions = drivers::FunctionMode::kAutoFallback;
  rig.start_streaming();
  EXPECT_TRUE(rig.axis->stats().fell_back_to_03_10);
  rig.enable_and_home();
  EXPECT_TRUE(rig.drive.position_at(hal::monotonic_now()) < 1e-3);
}

TEST(FhppAxis, WithoutFallbackAMissing0x17IsAConfigurationError) {
  sim::SimAxisServerConfig server;
  server.supports_read_write = false;
  ModbusRig rig(false, server);
  rig.make_axis();
  ASSERT_TRUE(rig.axis->start().ok);
  ASSERT_TRUE(wait_until([&] { return rig.axis->health().state == hal::DeviceState::kFault; }, 2s));
  EXPECT_NE(rig.axis->health().message.find("configuration error: exception 1"), std::string::npos)
      << rig.axis->health().message;
  EXPECT_EQ(rig.axis->health().counters.reconnects, 0u);
}

}  // namespace modbus_axis_test
}  // namespace rangefit::test
