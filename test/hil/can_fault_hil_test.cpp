// Hardware-in-the-loop fault injection (PROTOCOLS.md fault list) over the real Linux CAN stack:
// faults come from the simulated devices on their own socket, from can-utils (cansend) and from
// raw sockets; each test checks that the driver reports the fault (counters, health) and recovers.
// Interface down is in can_hil_test.cpp. Labelled `hil`: runs only in the VM (test/hil/run_vm.sh).
#include <gtest/gtest.h>
#include <time.h>

#include <algorithm>
#include <array>
#include <memory>
#include <thread>

#include "drivers/can/cia402_joint_source.hpp"
#include "drivers/can/powercube_joint_source.hpp"
#include "drivers/can/ranger_source.hpp"
#include "test/hil/can_hil_rig.hpp"
#include "test/support/can_cia402_node.hpp"
#include "test/support/can_powercube_module.hpp"
#include "test/support/can_profile_ranger.hpp"

namespace rangefit::drivers::can {
namespace can_fault_hil_test {

using namespace std::chrono_literals;
using test::cansend;
using test::eventually;
using test::socket_for;

// Two simulated CiA 402 drives (nodes 1 and 2, joints 5 and 6) on their own socket and the driver
// as SYNC master on another, both on the vcan interface.
class CanFaultHil : public ::testing::Test {
 protected:
  void start_cell() {
    config_.joints = {{1, 5, 1e-6, 0.0}, {2, 6, 1e-6, 0.0}};
    bus_ = test::sim_bus(false);
    ASSERT_NE(bus_, nullptr);
    n1_ = std::make_shared<sim::SimCia402Node>(sim::SimCia402Config{1});
    n2_ = std::make_shared<sim::SimCia402Node>(sim::SimCia402Config{2});
    n1_->set_angle(0.5);
    n2_->set_angle(-0.25);
    bus_->add(n1_);
    bus_->add(n2_);
    bus_->start();
    driver_ = std::make_unique<Cia402JointSource>(config_, socket_for(cia402_filter(config_)));
    ASSERT_TRUE(driver_->start().ok);
    ASSERT_GE(test::collect(*driver_, 20).size(), 20u);
    ASSERT_EQ(driver_->health().state, hal::DeviceState::kStreaming);
  }
  // A follower driver (no SYNC of its own, no NMT) for hand-made frames; with open_filter it
  // receives every id instead of its nodes' only.
  void start_follower(bool open_filter = false, int receive_buffer = 1 << 20) {
    config_.joints = {{1, 5, 1e-6, 0.0}, {2, 6, 1e-6, 0.0}};
    config_.sync_master = false;
    config_.start_nodes = false;
    FrameFilter filter = cia402_filter(config_);
    if (open_filter) filter.ids.clear();
    driver_ = std::make_unique<Cia402JointSource>(
        config_, socket_for(std::move(filter), false, receive_buffer));
    ASSERT_TRUE(driver_->start().ok);
  }
  void TearDown() override {
    if (driver_) driver_->stop();
    if (bus_) bus_->stop();
  }
  std::uint64_t count(Counter c) const { return driver_->counters()[c]; }
  // True once joint `joint` delivers a sample again.
  bool streams(std::uint8_t joint) {
    std::vector<hal::JointSample> out;
    return eventually([&] {
      driver_->read(out, 10ms);
      return std::any_of(out.begin(), out.end(), [&](const auto& s) { return s.joint == joint; });
    });
  }

  Cia402Config config_;
  std::unique_ptr<sim::SimCanBus> bus_;
  std::shared_ptr<sim::SimCia402Node> n1_, n2_;
  std::unique_ptr<Cia402JointSource> driver_;
};

TEST_F(CanFaultHil, SilentNodeIsReportedLostThenStreamsAgain) {
  start_cell();
  n2_->set_silent(true);
  ASSERT_TRUE(eventually([&] { return count(Counter::kNodesLost) >= 1; }));
  const hal::DeviceHealth h = driver_->health();
  EXPECT_EQ(h.state, hal::DeviceState::kFault);
  EXPECT_NE(h.message.find("node 2"), std::string::npos) << h.message;
  EXPECT_GT(count(Counter::kGaps), 0u);
  n2_->set_silent(false);
  ASSERT_TRUE(eventually([&] { return driver_->health().state == hal::DeviceState::kStreaming; }));
  EXPECT_TRUE(streams(6));
}

TEST_F(CanFaultHil, RebootedNodeIsCountedStartedAgainAndStreams) {
  start_cell();
  const auto reboots = count(Counter::kReboots);  // the nodes' first boot-ups may count too
  n1_->reboot();
  ASSERT_TRUE(eventually([&] { return count(Counter::kReboots) > reboots; }));
  EXPECT_TRUE(eventually([&] {
    return driver_->health().message.find("rebooted (node 1)") != std::string::npos;
  })) << driver_->health().message;
  // The boot-up heartbeat made the driver send NMT start again; the node answers SYNC again.
  ASSERT_TRUE(eventually([&] { return n1_->nmt_state() == cia402::kOperational; }));
  const auto answered = n1_->syncs_answered();
  EXPECT_TRUE(eventually([&] { return n1_->syncs_answered() > answered + 5; }));
  EXPECT_TRUE(streams(5));
}

TEST_F(CanFaultHil, MissingDuplicateAndShortTpdosAreCountedAndStreamingGoesOn) {
  start_cell();
  const auto gaps = count(Counter::kGaps);
  n1_->drop_next_tpdos(3);
  ASSERT_TRUE(eventually([&] { return count(Counter::kGaps) >= gaps + 3; }));
  n1_->duplicate_next_tpdo();
  ASSERT_TRUE(eventually([&] { return count(Counter::kDuplicates) >= 1; }));
  n1_->short_next_tpdo();
  ASSERT_TRUE(eventually([&] { return count(Counter::kBadLengths) >= 1; }));
  EXPECT_EQ(driver_->health().state, hal::DeviceState::kStreaming);
  EXPECT_TRUE(streams(5));
}

TEST_F(CanFaultHil, SyncGapsDuplicatesAndReorderingFromAForeignMasterAreCounted) {
  start_follower();
  auto master = socket_for({});
  ASSERT_TRUE(master->open().ok);
  const auto sync_and_answer = [&](std::uint8_t counter, bool answer) {
    ASSERT_EQ(master->send(cia402::encode_sync(counter)), TxResult::kOk);
    if (!answer) return;
    ASSERT_EQ(master->send(cia402::encode_tpdo1(1, 0x0637, counter * 1000)), TxResult::kOk);
    ASSERT_EQ(master->send(cia402::encode_tpdo1(2, 0x0637, counter * 1000)), TxResult::kOk);
  };
  sync_and_answer(1, true);
  sync_and_answer(2, true);
  sync_and_answer(2, false);  // duplicate SYNC
  sync_and_answer(4, true);   // SYNC 3 missing
  sync_and_answer(3, false);  // late, reordered SYNC 3
  const auto samples = test::collect(*driver_, 6);
  ASSERT_EQ(samples.size(), 6u);
  EXPECT_NEAR(samples[0].angle_rad, 1000e-6, 1e-12);
  EXPECT_NEAR(samples[5].angle_rad, 4000e-6, 1e-12);
  EXPECT_EQ(samples[4].stamp, samples[5].stamp);  // both joints of SYNC 4
  EXPECT_EQ(count(Counter::kDuplicates), 1u);
  EXPECT_EQ(count(Counter::kReordered), 1u);
  EXPECT_EQ(count(Counter::kGaps), 1u);
  // And the next cycle is taken normally.
  sync_and_answer(5, true);
  const auto more = test::collect(*driver_, 2);
  ASSERT_EQ(more.size(), 2u);
  EXPECT_NEAR(more[0].angle_rad, 5000e-6, 1e-12);
}

TEST_F(CanFaultHil, CansendShortFrameEmcyAndUnknownIdAreCounted) {
  // Node 2 sends no heartbeat here: under the VM's emulation the cansend processes took past the
  // 300 ms timeout, and "node silent" was reported in the EMCY's place.
  config_.heartbeat_timeout = 10s;
  start_follower(/*open_filter=*/true);  // unknown ids reach the driver's codec
  ASSERT_TRUE(cansend("080#01"));
  ASSERT_TRUE(cansend("181#3706"));  // TPDO1 of node 1 with 2 of 6 bytes
  ASSERT_TRUE(eventually([&] { return count(Counter::kBadLengths) >= 1; }));
  ASSERT_TRUE(cansend("082#1023010000000000"));  // EMCY 0x2310 from node 2
  ASSERT_TRUE(eventually([&] { return count(Counter::kFaults) >= 1; }));
  EXPECT_NE(driver_->health().message.find("EMCY received (node 2)"), std::string::npos)
      << driver_->health().message;
  ASSERT_TRUE(cansend("189#370600000000"));  // TPDO1 of node 9: not configured
  ASSERT_TRUE(eventually([&] { return count(Counter::kUnknownIds) >= 1; }));
  ASSERT_TRUE(cansend("080#02") && cansend("181#3706E8030000"));
  const auto samples = test::collect(*driver_, 1);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_NEAR(samples[0].angle_rad, 1000e-6, 1e-12);
}

TEST_F(CanFaultHil, ExactIdFiltersKeepUnknownIdsOutOfTheDriver) {
  start_follower();
  ASSERT_TRUE(cansend("189#370600000000"));
  ASSERT_TRUE(cansend("7FF#00"));
  ASSERT_TRUE(cansend("080#01") && cansend("181#3706E8030000"));
  ASSERT_EQ(test::collect(*driver_, 1).size(), 1u);  // frames are read in bus order
  EXPECT_EQ(count(Counter::kUnknownIds), 0u);
  EXPECT_EQ(driver_->counters().transport.rx_frames, 2u);
}

TEST_F(CanFaultHil, BusOffErrorPassiveAndRestartErrorFramesAreReportedAndStreamingRecovers) {
  start_cell();
  // vcan cannot go bus-off: inject the controller's error frames (CAN_ERR_FLAG ids) as a
  // real controller would send them.
  ASSERT_TRUE(cansend("20000040#0000000000000000"));  // CAN_ERR_BUSOFF
  ASSERT_TRUE(eventually([&] { return count(Counter::kBusOff) >= 1; }));
  hal::DeviceHealth h = driver_->health();
  EXPECT_EQ(h.state, hal::DeviceState::kFault);
  EXPECT_EQ(h.message, "bus-off");
  EXPECT_GE(h.counters.faults, 1u);
  ASSERT_TRUE(cansend("20000004#0010000000000000"));  // CAN_ERR_CRTL, CAN_ERR_CRTL_RX_PASSIVE
  ASSERT_TRUE(eventually([&] { return count(Counter::kErrorPassive) >= 1; }));
  ASSERT_TRUE(cansend("20000100#0000000000000000"));  // CAN_ERR_RESTARTED
  ASSERT_TRUE(eventually([&] { return count(Counter::kRestarts) >= 1; }));
  EXPECT_TRUE(eventually([&] { return driver_->health().state == hal::DeviceState::kStreaming; }));
  EXPECT_GE(count(Counter::kBusErrors), 3u);
  EXPECT_GE(driver_->counters().transport.error_frames, 3u);
  EXPECT_TRUE(streams(5));
}

TEST_F(CanFaultHil, ReceiveOverflowOfASmallSocketBufferIsCountedAndTheDriverGoesOn) {
  start_follower(false, /*receive_buffer=*/1);  // the kernel's minimum: a handful of frames
  auto flood = socket_for({});
  ASSERT_TRUE(flood->open().ok);
  const CanFrame heartbeat = cia402::encode_heartbeat(1, cia402::kOperational);
  const auto deadline = hal::monotonic_now() + 5s;
  while (driver_->counters().transport.rx_overflow == 0 && hal::monotonic_now() < deadline) {
    for (int i = 0; i < 2000; ++i) {
      if (flood->send(heartbeat) == TxResult::kBufferFull) std::this_thread::sleep_for(50us);
    }
  }
  ASSERT_GT(driver_->counters().transport.rx_overflow, 0u);
  EXPECT_GT(driver_->health().counters.dropped, 0u);
  std::this_thread::sleep_for(20ms);  // the flood drains
  ASSERT_EQ(flood->send(cia402::encode_sync(1)), TxResult::kOk);
  ASSERT_EQ(flood->send(cia402::encode_tpdo1(1, 0x0637, 2000)), TxResult::kOk);
  const auto samples = test::collect(*driver_, 1);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_NEAR(samples[0].angle_rad, 2000e-6, 1e-12);
}

// Steps CLOCK_REALTIME by `step` and back on destruction (root in the VM).
class WallClockStep {
 public:
  explicit WallClockStep(std::chrono::seconds step) : step_(step) { ok_ = shift(step_); }
  ~WallClockStep() {
    if (ok_) shift(-step_);
  }
  bool ok() const { return ok_; }

 private:
  static bool shift(std::chrono::seconds s) {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    ts.tv_sec += s.count();
    return clock_settime(CLOCK_REALTIME, &ts) == 0;
  }
  std::chrono::seconds step_;
  bool ok_ = false;
};

TEST(CanFaultHilStamps, WallClockStepsMakeBadStampsThatFallBackToTheReadTimeThenRecover) {
  auto rx = socket_for({{0x123}});
  auto tx = socket_for({});
  ASSERT_TRUE(rx->open().ok && tx->open().ok);
  std::array<CanFrame, 8> in{};
  const auto receive = [&](std::size_t n) {
    std::size_t got = 0;
    eventually([&] {
      got += rx->receive(std::span(in).subspan(got), 10ms).frames;
      return got >= n;
    });
    return got;
  };
  ASSERT_EQ(tx->send(make_frame(0x123, {})), TxResult::kOk);
  ASSERT_EQ(receive(1), 1u);
  EXPECT_EQ(rx->counters().bad_stamps, 0u);
  for (const auto step : {10s, -10s}) {
    // Frames stamped before the step, read after it: their kernel stamps (CLOCK_REALTIME) are
    // 10 s off the new offset, so they are replaced by the read time and the step is counted.
    const auto bad = rx->counters().bad_stamps;
    const auto steps = rx->counters().clock_steps;
    for (int i = 0; i < 3; ++i) ASSERT_EQ(tx->send(make_frame(0x123, {})), TxResult::kOk);
    std::this_thread::sleep_for(20ms);
    const hal::Timestamp before = hal::monotonic_now();
    {
      WallClockStep clock_step(step);
      ASSERT_TRUE(clock_step.ok());
      ASSERT_EQ(receive(3), 3u);
      const hal::Timestamp after = hal::monotonic_now();
      EXPECT_EQ(rx->counters().bad_stamps, bad + 3);
      EXPECT_EQ(rx->counters().clock_steps, steps + 1);
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_GE(in[i].stamp, before);
        EXPECT_LE(in[i].stamp, after);
      }
      // Frames sent after the step are stamped normally again.
      const hal::Timestamp sent = hal::monotonic_now();
      ASSERT_EQ(tx->send(make_frame(0x123, {})), TxResult::kOk);
      ASSERT_EQ(receive(1), 1u);
      EXPECT_EQ(rx->counters().bad_stamps, bad + 3);
      EXPECT_GE(in[0].stamp, sent - 1ms);
      EXPECT_LE(in[0].stamp, hal::monotonic_now());
    }
    ASSERT_EQ(tx->send(make_frame(0x123, {})), TxResult::kOk);  // read after stepping back
    ASSERT_EQ(receive(1), 1u);
  }
}

TEST(CanFaultHilDevices, SilentPowerCubeModuleTimesOutIsReportedAndRecovers) {
  PowerCubeConfig cfg;
  cfg.modules = {{3, 1, 0.0}, {4, 2, 0.0}};
  cfg.reply_timeout = 20ms;
  auto bus = test::sim_bus(false);
  ASSERT_NE(bus, nullptr);
  auto m3 = std::make_shared<sim::SimPowerCubeModule>(3);
  auto m4 = std::make_shared<sim::SimPowerCubeModule>(4);
  bus->add(m3);
  bus->add(m4);
  bus->start();
  PowerCubeJointSource driver(cfg, socket_for(powercube_filter(cfg)));
  ASSERT_TRUE(driver.start().ok);
  ASSERT_GE(test::collect(driver, 10).size(), 10u);
  m4->set_silent(true);
  ASSERT_TRUE(eventually([&] { return driver.counters()[Counter::kNodesLost] >= 1; }));
  EXPECT_GE(driver.counters()[Counter::kTimeouts], 3u);
  EXPECT_EQ(driver.health().state, hal::DeviceState::kFault);
  EXPECT_NE(driver.health().message.find("node 4"), std::string::npos);
  m4->set_silent(false);
  EXPECT_TRUE(eventually([&] { return driver.health().state == hal::DeviceState::kStreaming; }));
  driver.stop();
  bus->stop();
}

TEST(CanFaultHilDevices, RangerLostSegmentCrcErrorAndSequenceGapAreCountedAndStreamGoesOn) {
  RangerConfig cfg;
  cfg.node = 0x23;
  auto bus = test::sim_bus(true);
  ASSERT_NE(bus, nullptr);
  sim::SimRangerConfig rc;
  rc.node = 0x23;
  auto ranger = std::make_shared<sim::SimProfileRanger>(rc);
  bus->add(ranger);
  RangerCanSource driver(cfg, socket_for(ranger_filter(cfg), true));
  ASSERT_TRUE(driver.start().ok);
  bus->start();
  ASSERT_GE(test::collect(driver, 5).size(), 5u);
  const auto count = [&](Counter c) { return driver.counters()[c]; };
  ranger->drop_segment_next(5);
  ASSERT_TRUE(eventually([&] { return count(Counter::kTimeouts) >= 1; }));
  ranger->corrupt_crc_next();
  ASSERT_TRUE(eventually([&] { return count(Counter::kCrcErrors) >= 1; }));
  const auto gaps = count(Counter::kGaps);
  ranger->skip_sequences(4);
  ASSERT_TRUE(eventually([&] { return count(Counter::kGaps) >= gaps + 4; }));
  std::vector<hal::RangerProfile> before_gap;
  driver.read(before_gap, 0ms);  // what was queued up to the gap
  const auto after = test::collect(driver, 5);
  ASSERT_GE(after.size(), 5u);
  for (std::size_t i = 1; i < after.size(); ++i) {
    EXPECT_EQ(after[i].sequence, after[i - 1].sequence + 1);
  }
  EXPECT_EQ(driver.health().state, hal::DeviceState::kStreaming);
  driver.stop();
  bus->stop();
}

}  // namespace can_fault_hil_test
}  // namespace rangefit::drivers::can
