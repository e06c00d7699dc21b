// The CAN FD ranger driver reassembling a simulated ranger's 100 Hz profile stream over the
// in-process transport: values, stamps, and the profile faults (lost segment, CRC, gaps).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <span>
#include <thread>

#include "drivers/can/ranger_source.hpp"
#include "hal/stripe_geometry.hpp"
#include "test/drivers/can_test_rig.hpp"
#include "test/support/can_profile_ranger.hpp"
#include "test/support/inprocess_transport.hpp"

namespace rangefit::drivers::can {
namespace can_ranger_driver_test {

using namespace std::chrono_literals;
using test::eventually;

class RangerDriver : public ::testing::Test {
 protected:
  void SetUp() override {
    config_.node = 0x21;
    config_.lateral_pitch_mm = 0.05;
    config_.range_offset_mm = 60.0;
    t0_ = hal::monotonic_now();
    sim::SimRangerConfig rc;
    rc.node = 0x21;
    rc.rate_hz = 100;
    rc.units_um = 4;
    ranger_ = std::make_shared<sim::SimProfileRanger>(rc, [](std::uint32_t seq, hal::Timestamp,
                                                             std::span<std::uint16_t> range) {
      for (std::size_t k = 0; k < range.size(); ++k) {
        range[k] = k == 7 ? std::uint16_t{0xFFFF} : static_cast<std::uint16_t>(1000 + k + seq % 10);
      }
    });
    rig_.wire(config_, ranger_filter(config_), {ranger_});
    driver_ = rig_.driver.get();
    ASSERT_TRUE(driver_->start().ok);
    rig_.bus->start();
  }
  std::vector<hal::RangerProfile> collect(std::size_t n) { return test::collect(*driver_, n); }
  std::uint64_t count(Counter c) const { return driver_->counters()[c]; }

  RangerConfig config_;
  hal::Timestamp t0_{};
  std::shared_ptr<sim::SimProfileRanger> ranger_;
  test::InProcessRig<RangerCanSource> rig_;
  RangerCanSource* driver_ = nullptr;
};

TEST_F(RangerDriver, ProfilesAt100HzArriveCompleteInOrderWithValues) {
  const auto profiles = collect(20);
  ASSERT_GE(profiles.size(), 20u);
  for (std::size_t i = 0; i < profiles.size(); ++i) {
    const auto& p = profiles[i];
    ASSERT_EQ(p.z_mm.size(), 512u);
    ASSERT_EQ(p.x_mm.size(), 512u);
    if (i > 0) {
      EXPECT_EQ(p.sequence, profiles[i - 1].sequence + 1);
      EXPECT_GT(p.stamp, profiles[i - 1].stamp);
    }
    EXPECT_GT(p.stamp, t0_ - 1ms);
    EXPECT_EQ(p.exposure, 500us);
    EXPECT_TRUE(std::isnan(p.z_mm[7]));
    EXPECT_NEAR(p.z_mm[0], 60.0 + (1000 + p.sequence % 10) * 0.004, 1e-4);
    EXPECT_NEAR(p.z_mm[511], 60.0 + (1000 + 511 + p.sequence % 10) * 0.004, 1e-4);
    EXPECT_NEAR(p.x_mm[0], -255.5 * 0.05, 1e-4);
    EXPECT_NEAR(p.x_mm[511], 255.5 * 0.05, 1e-4);
  }
  EXPECT_EQ(count(Counter::kGaps), 0u);
  EXPECT_EQ(count(Counter::kCrcErrors), 0u);
  EXPECT_EQ(count(Counter::kTimeouts), 0u);
  EXPECT_EQ(driver_->health().state, hal::DeviceState::kStreaming);
}

// A fan laser (the cell's and the head's ranger, hal::StripeRanger): every point lies on the fan
// ray of its column, where fusion and the simulator put it.
class FanRangerDriver : public RangerDriver {
 protected:
  void SetUp() override {
    config_.fan_angle_rad = 0.5;
    RangerDriver::SetUp();
  }
};

TEST_F(FanRangerDriver, EveryPointLiesOnTheFanRayOfItsColumn) {
  const auto profiles = collect(3);
  ASSERT_GE(profiles.size(), 3u);
  const hal::StripeRanger fan{.fan_angle_rad = 0.5};
  for (const auto& p : profiles) {
    ASSERT_EQ(p.x_mm.size(), 512u);
    for (int k : {0, 100, 255, 256, 511}) {
      const auto i = static_cast<std::size_t>(k);
      EXPECT_NEAR(p.z_mm[i], 60.0 + (1000 + k + p.sequence % 10) * 0.004, 1e-4);
      EXPECT_NEAR(std::atan2(p.x_mm[i], p.z_mm[i]), fan.ray_angle(k, 512), 1e-6) << k;
    }
    EXPECT_NEAR(p.x_mm[0], -p.z_mm[0] * std::tan(0.25), 1e-3);
    EXPECT_TRUE(std::isnan(p.x_mm[7]) && std::isnan(p.z_mm[7])) << "no return has no point";
  }
}

TEST_F(RangerDriver, DeviceClockIsMappedToTheExposureCentre) {
  const auto profiles = collect(30);
  ASSERT_GE(profiles.size(), 30u);
  // The profile is read out half an exposure after its centre and arrives shortly after; the
  // mapped stamp must lie before the arrival and within a few ms of it.
  const hal::Timestamp now = hal::monotonic_now();
  const auto& last = profiles.back();
  EXPECT_LT(last.stamp, now);
  // Successive stamps follow the device's 10 ms period, not the arrival jitter.
  const auto span = profiles[29].stamp - profiles[9].stamp;
  const double period_ms = std::chrono::duration<double, std::milli>(span).count() /
                           static_cast<double>(profiles[29].sequence - profiles[9].sequence);
  EXPECT_NEAR(period_ms, 10.0, 1.0);
}

TEST_F(RangerDriver, LostSegmentCorruptCrcAndSkippedSequencesAreCounted) {
  collect(3);
  ranger_->drop_segment_next(5);
  ASSERT_TRUE(eventually([&] { return count(Counter::kTimeouts) >= 1; }));
  ranger_->corrupt_crc_next();
  ASSERT_TRUE(eventually([&] { return count(Counter::kCrcErrors) >= 1; }));
  const auto gaps = count(Counter::kGaps);
  ranger_->skip_sequences(4);
  ASSERT_TRUE(eventually([&] { return count(Counter::kGaps) >= gaps + 4; }));
  EXPECT_FALSE(collect(3).empty());  // and the stream goes on
}

TEST_F(RangerDriver, SilentRangerIsReportedLostAndRecovers) {
  collect(3);
  ranger_->set_silent(true);
  ASSERT_TRUE(eventually([&] { return count(Counter::kNodesLost) >= 1; }));
  EXPECT_EQ(driver_->health().state, hal::DeviceState::kFault);
  ranger_->set_silent(false);
  ASSERT_TRUE(eventually([&] { return driver_->health().state == hal::DeviceState::kStreaming; }));
}

}  // namespace can_ranger_driver_test
}  // namespace rangefit::drivers::can
