// The CiA 402 joint driver against simulated CiA 402 drives speaking the wire protocol over the
// in-process transport: values and stamps, start-up (NMT, SDO, the nodes' serial numbers), and the
// CAN fault list.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <thread>

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include "drivers/can/cia402_joint_source.hpp"
#include "drivers/can/cia402_pan_tilt_source.hpp"
#include "test/drivers/can_test_rig.hpp"
#include "test/support/can_cia402_node.hpp"
#include "test/support/inprocess_transport.hpp"

namespace rangefit::drivers::can {
namespace can_cia402_driver_test {

using namespace std::chrono_literals;
using test::eventually;

constexpr double kOmega = 1.0;  // rad/s of the simulated joints

// Captures what the driver logs while it lives (the default logger's sink, restored after).
class LogCapture {
 public:
  LogCapture()
      : sink_(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(64)),
        previous_(spdlog::default_logger()) {
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", sink_));
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  int count(const std::string& text) const {
    const auto lines = sink_->last_formatted();
    return static_cast<int>(std::count_if(lines.begin(), lines.end(), [&](const auto& l) {
      return l.find(text) != std::string::npos;
    }));
  }

 private:
  std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> sink_;
  std::shared_ptr<spdlog::logger> previous_;
};

class Cia402Driver : public ::testing::Test {
 protected:
  void start(bool master = true, sim::SimIdentityReply node2_identity = sim::SimIdentityReply::kSerial) {
    config_.sync_master = master;
    config_.joints = {{1, 5, 1e-6, 0.0}, {2, 6, 1e-6, 0.0}};
    t0_ = hal::monotonic_now();
    const auto angle = [t0 = t0_](hal::Timestamp t) {
      return kOmega * std::chrono::duration<double>(t - t0).count();
    };
    sim::SimCia402Config n1;
    n1.node = 1;
    n1.heartbeat_ms = 1000;  // the driver configures 100 ms by SDO
    sim::SimCia402Config n2 = n1;
    n2.node = 2;
    n2.identity = node2_identity;
    node1_ = std::make_shared<sim::SimCia402Node>(n1, angle);
    node2_ = std::make_shared<sim::SimCia402Node>(n2, angle);
    if (master) {
      rig_.wire(config_, cia402_filter(config_), {node1_, node2_});
    } else {
      rig_.wire(config_, cia402_filter(config_), {});
    }
    rig_.bus->start();
    ASSERT_TRUE(rig_.driver->start().ok);
    driver_ = rig_.driver.get();
    link_ = rig_.link;
    sim_link_ = rig_.sim_link;
  }
  std::vector<hal::JointSample> collect(std::size_t n) { return test::collect(*driver_, n); }
  std::uint64_t count(Counter c) const { return driver_->counters()[c]; }

  Cia402Config config_;
  test::InProcessRig<Cia402JointSource> rig_;
  Cia402JointSource* driver_ = nullptr;
  InProcessTransport* link_ = nullptr;
  InProcessTransport* sim_link_ = nullptr;
  std::shared_ptr<sim::SimCia402Node> node1_, node2_;
  hal::Timestamp t0_{};
};

TEST(Cia402DriverConfig, NoJointsIsRefusedAtStart) {
  auto [a, b] = InProcessTransport::make_pair();
  Cia402JointSource driver(Cia402Config{}, std::move(a));
  const hal::Status s = driver.start();
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.message.find("no joints"), std::string::npos);
}

TEST_F(Cia402Driver, StartsNodesConfiguresHeartbeatAndStreamsJointAnglesAtSyncStamps) {
  start();
  const auto samples = collect(100);
  ASSERT_GE(samples.size(), 100u);
  EXPECT_EQ(node1_->nmt_state(), cia402::kOperational);
  EXPECT_EQ(node1_->heartbeat_ms(), 100);
  hal::Timestamp last5{};
  int joint5 = 0;
  for (const auto& s : samples) {
    ASSERT_TRUE(s.joint == 5 || s.joint == 6);
    EXPECT_TRUE(s.valid);
    EXPECT_EQ(s.status, 0x0637);
    // The drive sampled its angle when it received the SYNC; the driver stamps the SYNC echo.
    const double expected = kOmega * std::chrono::duration<double>(s.stamp - t0_).count();
    EXPECT_NEAR(s.angle_rad, expected, 0.02);
    if (s.joint == 5) {
      EXPECT_GT(s.stamp, last5);
      last5 = s.stamp;
      ++joint5;
    }
  }
  EXPECT_GE(joint5, 40);
  EXPECT_EQ(driver_->health().state, hal::DeviceState::kStreaming);
}

TEST_F(Cia402Driver, ReportsEachNodesSerialAsHardwareIdOnceTheNodesAnswered) {
  start();
  // The simulated drives hold 402001 and 402002 in 0x1018:04.
  ASSERT_TRUE(eventually([&] { return driver_->health().hardware_id == "1:402001 2:402002"; }))
      << driver_->health().hardware_id;
  EXPECT_EQ(driver_->identity(1), Cia402JointSource::Identity::kKnown);
  EXPECT_EQ(node1_->identity_requests(), 1u) << "asked once, after the heartbeat was configured";
  EXPECT_EQ(node1_->heartbeat_ms(), 100);
  EXPECT_EQ(count(Counter::kFaults), 0u);
}

TEST_F(Cia402Driver, NodeThatNeverAnswersTheSerialKeepsItsNameIsLoggedOnceAndStreams) {
  LogCapture log;
  start(/*master=*/true, sim::SimIdentityReply::kSilent);
  ASSERT_TRUE(eventually([&] {
    return driver_->identity(2) == Cia402JointSource::Identity::kNoAnswer &&
           driver_->identity(1) == Cia402JointSource::Identity::kKnown;
  }));
  EXPECT_EQ(node2_->identity_requests(), 1u);
  for (int i = 0; i < 5; ++i) {
    const hal::DeviceHealth h = driver_->health();
    EXPECT_EQ(h.hardware_id, "1:402001") << "only the node that answered";
    EXPECT_EQ(h.state, hal::DeviceState::kStreaming);
  }
  EXPECT_EQ(log.count("node 2 gave no serial number (0x1018:04 not answered within 200 ms)"), 1);
  EXPECT_EQ(log.count("node 1 gave no serial"), 0);
  std::vector<hal::JointSample> out;
  EXPECT_TRUE(eventually([&] {
    driver_->read(out, 10ms);
    return std::count_if(out.begin(), out.end(), [](const auto& s) { return s.joint == 6; }) >= 20;
  })) << "the silent node's joint keeps streaming";
}

TEST_F(Cia402Driver, NodeWithoutSerialObjectIsNotAFault) {
  LogCapture log;
  start(/*master=*/true, sim::SimIdentityReply::kAbort);
  ASSERT_TRUE(eventually(
      [&] { return driver_->identity(2) == Cia402JointSource::Identity::kAborted; }));
  ASSERT_TRUE(eventually([&] { return driver_->health().hardware_id == "1:402001"; }));
  EXPECT_EQ(log.count("node 2 gave no serial number (0x1018:04 refused, SDO abort 0x06090011)"), 1);
  collect(20);
  EXPECT_EQ(count(Counter::kFaults), 0u);
  EXPECT_EQ(driver_->health().state, hal::DeviceState::kStreaming);
}

TEST_F(Cia402Driver, SwappedNodeIsNamedByTheNewSerialAfterItsBootUp) {
  start();
  ASSERT_TRUE(eventually([&] { return driver_->health().hardware_id == "1:402001 2:402002"; }));
  node1_->set_serial(77001);
  node1_->reboot();
  ASSERT_TRUE(eventually([&] { return driver_->health().hardware_id == "1:77001 2:402002"; }))
      << driver_->health().hardware_id;
  EXPECT_EQ(node1_->identity_requests(), 2u);
}

TEST_F(Cia402Driver, BothJointsOfOneSyncShareItsStamp) {
  start();
  const auto samples = collect(40);
  std::map<std::int64_t, int> per_stamp;
  for (const auto& s : samples) ++per_stamp[s.stamp.count()];
  int paired = 0;
  for (const auto& [stamp, n] : per_stamp) paired += n == 2;
  EXPECT_GE(paired, 15);
}

TEST_F(Cia402Driver, SilentNodeIsReportedLostAndRecovers) {
  start();
  collect(10);
  node2_->set_silent(true);
  ASSERT_TRUE(eventually([&] { return count(Counter::kNodesLost) >= 1; }));
  const hal::DeviceHealth h = driver_->health();
  EXPECT_EQ(h.state, hal::DeviceState::kFault);
  EXPECT_NE(h.message.find("node 2"), std::string::npos);
  EXPECT_GT(count(Counter::kGaps), 0u);
  node2_->set_silent(false);
  ASSERT_TRUE(eventually([&] { return driver_->health().state == hal::DeviceState::kStreaming; }));
  std::vector<hal::JointSample> out;
  ASSERT_TRUE(eventually([&] {
    driver_->read(out, 10ms);
    return !out.empty() && out.back().joint == 6;
  }));
}

TEST_F(Cia402Driver, RebootedNodeIsCountedAndStartedAgain) {
  start();
  collect(10);
  const auto before = count(Counter::kReboots);
  node1_->reboot();
  ASSERT_TRUE(eventually([&] { return count(Counter::kReboots) > before; }));
  ASSERT_TRUE(eventually([&] { return node1_->nmt_state() == cia402::kOperational; }));
  const auto answered = node1_->syncs_answered();
  EXPECT_TRUE(eventually([&] { return node1_->syncs_answered() > answered + 5; }));
}

TEST_F(Cia402Driver, MissingDuplicateAndShortTpdosAreCountedNotDelivered) {
  start();
  collect(10);
  const auto gaps = count(Counter::kGaps);
  node1_->drop_next_tpdos(3);
  ASSERT_TRUE(eventually([&] { return count(Counter::kGaps) >= gaps + 3; }));
  node1_->duplicate_next_tpdo();
  ASSERT_TRUE(eventually([&] { return count(Counter::kDuplicates) >= 1; }));
  node1_->short_next_tpdo();
  ASSERT_TRUE(eventually([&] { return count(Counter::kBadLengths) >= 1; }));
  EXPECT_EQ(driver_->health().state, hal::DeviceState::kStreaming);
}

TEST_F(Cia402Driver, EmcyAndFaultBitAreReported) {
  start();
  collect(10);
  node2_->send_emcy_next(0x2310);
  ASSERT_TRUE(eventually([&] { return count(Counter::kFaults) >= 1; }));
  EXPECT_NE(driver_->health().message.find("EMCY"), std::string::npos);
  node1_->set_fault(true);
  std::vector<hal::JointSample> out;
  EXPECT_TRUE(eventually([&] {
    driver_->read(out, 10ms);
    return std::any_of(out.begin(), out.end(),
                       [](const auto& s) { return s.joint == 5 && !s.valid; });
  }));
}

TEST_F(Cia402Driver, UnknownIdsAreCountedWhenNotFilteredOut) {
  start();
  FrameFilter open = cia402_filter(config_);
  open.ids.clear();
  link_->set_filter(open);
  ASSERT_EQ(sim_link_->send(cia402::encode_tpdo1(9, 0, 0)), TxResult::kOk);  // node 9: not ours
  ASSERT_TRUE(eventually([&] { return count(Counter::kUnknownIds) >= 1; }));
}

TEST_F(Cia402Driver, DownedInterfaceIsReopenedAndStreamingResumes) {
  start();
  collect(10);
  link_->set_link_down(true);
  ASSERT_TRUE(
      eventually([&] { return driver_->health().state == hal::DeviceState::kDisconnected; }));
  EXPECT_NE(driver_->health().message.find("interface down"), std::string::npos);
  link_->set_link_down(false);
  ASSERT_TRUE(eventually([&] { return count(Counter::kReconnects) >= 1; }));
  std::vector<hal::JointSample> out;
  driver_->read(out, 0ms);
  out.clear();
  EXPECT_FALSE(collect(10).empty());
}

TEST_F(Cia402Driver, FollowerCountsSyncGapsDuplicatesAndReordering) {
  start(/*master=*/false);
  auto& bus = *sim_link_;
  const auto sync_and_answer = [&](std::uint8_t counter, bool answer) {
    ASSERT_EQ(bus.send(cia402::encode_sync(counter)), TxResult::kOk);
    if (!answer) return;
    ASSERT_EQ(bus.send(cia402::encode_tpdo1(1, 0x0637, counter * 1000)), TxResult::kOk);
    ASSERT_EQ(bus.send(cia402::encode_tpdo1(2, 0x0637, counter * 1000)), TxResult::kOk);
  };
  sync_and_answer(1, true);
  sync_and_answer(2, true);
  sync_and_answer(2, false);  // duplicate SYNC
  sync_and_answer(4, true);   // SYNC 3 missing
  sync_and_answer(3, false);  // late, reordered SYNC 3
  const auto samples = collect(6);
  ASSERT_EQ(samples.size(), 6u);
  EXPECT_NEAR(samples[0].angle_rad, 1000e-6, 1e-12);
  EXPECT_NEAR(samples[5].angle_rad, 4000e-6, 1e-12);
  EXPECT_EQ(samples[4].stamp, samples[5].stamp);
  EXPECT_EQ(count(Counter::kDuplicates), 1u);
  EXPECT_EQ(count(Counter::kReordered), 1u);
  EXPECT_EQ(count(Counter::kGaps), 1u);
}

TEST(Cia402OneJoint, HardwareIdIsTheNodesSerialAlone) {
  Cia402Config config;
  config.name = "robot.j3";
  config.joints = {{7, 3, 1e-6, 0.0}};
  sim::SimCia402Config n;
  n.node = 7;
  n.serial = 123456789;
  auto node = std::make_shared<sim::SimCia402Node>(n);
  test::InProcessRig<Cia402JointSource> rig;
  rig.wire(config, cia402_filter(config), {node});
  rig.bus->start();
  ASSERT_TRUE(rig.driver->start().ok);
  EXPECT_TRUE(eventually([&] { return rig.driver->health().hardware_id == "123456789"; }))
      << rig.driver->health().hardware_id;
}

TEST(Cia402PanTilt, PairsPanAndTiltOfTheSameSync) {
  PanTiltConfig config;
  config.pan = {3, 1, 1e-6, 0.0};
  config.tilt = {4, 2, 1e-6, 0.0};
  auto pan = std::make_shared<sim::SimCia402Node>(sim::SimCia402Config{3});
  auto tilt = std::make_shared<sim::SimCia402Node>(sim::SimCia402Config{4});
  pan->set_angle(0.3);
  tilt->set_angle(-0.2);
  test::InProcessRig<Cia402PanTiltSource> rig;
  rig.wire(config, cia402_filter(pan_tilt_bus_config(config)), {pan, tilt});
  rig.bus->start();
  ASSERT_TRUE(rig.driver->start().ok);
  const auto out = test::collect(*rig.driver, 10);
  EXPECT_TRUE(eventually([&] { return rig.driver->health().hardware_id == "3:402003 4:402004"; }))
      << rig.driver->health().hardware_id;
  rig.stop();
  ASSERT_GE(out.size(), 10u);
  for (const auto& s : out) {
    EXPECT_NEAR(s.pan_rad, 0.3, 1e-6);
    EXPECT_NEAR(s.tilt_rad, -0.2, 1e-6);
    EXPECT_TRUE(s.valid);
  }
}

}  // namespace can_cia402_driver_test
}  // namespace rangefit::drivers::can
