// The PowerCube joint driver polling simulated PowerCube modules over the in-process transport.
#include <gtest/gtest.h>

#include <memory>
#include <thread>

#include "drivers/can/powercube_joint_source.hpp"
#include "test/drivers/can_test_rig.hpp"
#include "test/support/can_powercube_module.hpp"
#include "test/support/inprocess_transport.hpp"

namespace rangefit::drivers::can {
namespace can_powercube_driver_test {

using namespace std::chrono_literals;
using test::eventually;

class PowerCubeDriver : public ::testing::Test {
 protected:
  void SetUp() override {
    config_.modules = {{4, 5, 0.0}, {5, 6, 0.1}};
    config_.poll_period = 5ms;
    m4_ = std::make_shared<sim::SimPowerCubeModule>(4);
    m5_ = std::make_shared<sim::SimPowerCubeModule>(5);
    m4_->set_angle(1.5);
    m5_->set_angle(-0.5);
    rig_.wire(config_, powercube_filter(config_), {m4_, m5_});
    rig_.bus->start();
    driver_ = rig_.driver.get();
    ASSERT_TRUE(driver_->start().ok);
  }
  std::uint64_t count(Counter c) const { return driver_->counters()[c]; }

  PowerCubeConfig config_;
  std::shared_ptr<sim::SimPowerCubeModule> m4_, m5_;
  test::InProcessRig<PowerCubeJointSource> rig_;
  PowerCubeJointSource* driver_ = nullptr;
};

TEST(PowerCubeDriverConfig, NoModulesIsRefusedAtStart) {
  auto [a, b] = InProcessTransport::make_pair();
  PowerCubeJointSource driver(PowerCubeConfig{}, std::move(a));
  EXPECT_FALSE(driver.start().ok);
}

TEST_F(PowerCubeDriver, PolledPositionsArriveWithOffsetsAndReplyStamps) {
  std::vector<hal::JointSample> out;
  const hal::Timestamp before = hal::monotonic_now();
  ASSERT_TRUE(eventually([&] {
    driver_->read(out, 10ms);
    return out.size() >= 40;
  }));
  int j5 = 0, j6 = 0;
  hal::Timestamp last{};
  for (const auto& s : out) {
    EXPECT_GT(s.stamp, before);
    EXPECT_GE(s.stamp, last);  // one request at a time: replies come in order
    last = s.stamp;
    if (s.joint == 5) {
      ++j5;
      EXPECT_NEAR(s.angle_rad, 1.5, 1e-6);
    } else {
      ++j6;
      EXPECT_NEAR(s.angle_rad, -0.5 + 0.1, 1e-6);
    }
    EXPECT_TRUE(s.valid);
  }
  EXPECT_GE(j5, 15);
  EXPECT_GE(j6, 15);
}

TEST_F(PowerCubeDriver, SilentModuleTimesOutIsReportedAndRecovers) {
  m5_->set_silent(true);
  ASSERT_TRUE(eventually([&] { return count(Counter::kNodesLost) >= 1; }));
  EXPECT_GE(count(Counter::kTimeouts), 3u);
  EXPECT_EQ(driver_->health().state, hal::DeviceState::kFault);
  // The other module keeps streaming meanwhile.
  std::vector<hal::JointSample> out;
  ASSERT_TRUE(eventually([&] {
    driver_->read(out, 10ms);
    return !out.empty() && out.back().joint == 5;
  }));
  m5_->set_silent(false);
  ASSERT_TRUE(eventually([&] { return driver_->health().state == hal::DeviceState::kStreaming; }));
}

TEST_F(PowerCubeDriver, NotOkStateMarksSamplesInvalidAndShortRepliesAreCounted) {
  m4_->set_not_ok(true);
  std::vector<hal::JointSample> out;
  ASSERT_TRUE(eventually([&] {
    driver_->read(out, 10ms);
    return !out.empty() && out.back().joint == 5 && !out.back().valid;
  }));
  EXPECT_GE(count(Counter::kFaults), 1u);
  m4_->short_next_reply();
  ASSERT_TRUE(eventually([&] { return count(Counter::kBadLengths) >= 1; }));
}

}  // namespace can_powercube_driver_test
}  // namespace rangefit::drivers::can
