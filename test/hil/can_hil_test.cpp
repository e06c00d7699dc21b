// Hardware-in-the-loop: the CAN drivers over the real Linux CAN stack (vcan0 inside the qemu VM,
// test/hil/run_vm.sh), against simulated devices on their own sockets and against can-utils
// (candump/cansend) as independent peers. Labelled `hil`: AF_CAN does not exist on the host.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "drivers/can/cia402_joint_source.hpp"
#include "drivers/can/powercube_joint_source.hpp"
#include "drivers/can/ranger_source.hpp"
#include "drivers/can/socketcan_transport.hpp"
#include "test/hil/can_hil_rig.hpp"
#include "test/support/can_cia402_node.hpp"
#include "test/support/can_powercube_module.hpp"
#include "test/support/can_profile_ranger.hpp"

namespace rangefit::drivers::can {
namespace can_hil_test {

using namespace std::chrono_literals;
using test::cansend;
using test::eventually;
using test::interface;
using test::sim_bus;
using test::socket_for;

TEST(CanHil, Cia402JointsArriveWithValuesAndSyncStampsAndSurviveInterfaceDown) {
  Cia402Config cfg;
  cfg.joints = {{1, 5, 1e-6, 0.0}, {2, 6, 1e-6, 0.0}};
  auto bus = sim_bus(false);
  ASSERT_NE(bus, nullptr);
  const hal::Timestamp t0 = hal::monotonic_now();
  const auto angle = [t0](hal::Timestamp t) {
    return std::chrono::duration<double>(t - t0).count();
  };
  auto n1 = std::make_shared<sim::SimCia402Node>(sim::SimCia402Config{1}, angle);
  auto n2 = std::make_shared<sim::SimCia402Node>(sim::SimCia402Config{2}, angle);
  bus->add(n1);
  bus->add(n2);
  bus->start();
  Cia402JointSource driver(cfg, socket_for(cia402_filter(cfg)));
  ASSERT_TRUE(driver.start().ok);
  std::vector<hal::JointSample> out;
  ASSERT_TRUE(eventually([&] {
    driver.read(out, 10ms);
    return out.size() >= 100;
  }));
  // The joints turn at 1 rad/s, so the angle error in rad is the stamp error in s. Typically the
  // TPDO answers its own SYNC; when the VM stalls the simulated node for longer than a cycle,
  // its late TPDO belongs to a later SYNC (TPDOs carry no counter), hence the looser bound.
  std::vector<double> error;
  for (const auto& s : out) {
    error.push_back(std::abs(s.angle_rad - std::chrono::duration<double>(s.stamp - t0).count()));
  }
  std::sort(error.begin(), error.end());
  EXPECT_LT(error[error.size() / 2], 0.002);
  EXPECT_LT(error.back(), 0.1);
  EXPECT_EQ(driver.counters().transport.rx_overflow, 0u);
  ASSERT_TRUE(test::set_link(false));
  const bool disconnected =
      eventually([&] { return driver.health().state == hal::DeviceState::kDisconnected; });
  ASSERT_TRUE(test::set_link(true));  // before any assertion can end the test: later tests need it
  ASSERT_TRUE(disconnected);
  ASSERT_TRUE(eventually([&] { return driver.counters()[Counter::kReconnects] >= 1; }));
  out.clear();
  EXPECT_TRUE(eventually([&] {
    driver.read(out, 10ms);
    return out.size() >= 10;
  }));
  driver.stop();
  bus->stop();
}

TEST(CanHil, PowerCubeModulesAnswerPolls) {
  PowerCubeConfig cfg;
  cfg.modules = {{3, 1, 0.0}};
  cfg.reply_timeout = 20ms;
  auto bus = sim_bus(false);
  ASSERT_NE(bus, nullptr);
  auto m = std::make_shared<sim::SimPowerCubeModule>(3);
  m->set_angle(0.75);
  bus->add(m);
  bus->start();
  PowerCubeJointSource driver(cfg, socket_for(powercube_filter(cfg)));
  ASSERT_TRUE(driver.start().ok);
  std::vector<hal::JointSample> out;
  ASSERT_TRUE(eventually([&] {
    driver.read(out, 10ms);
    return out.size() >= 20;
  }));
  for (const auto& s : out) EXPECT_NEAR(s.angle_rad, 0.75, 1e-6);
  driver.stop();
  bus->stop();
}

TEST(CanHil, RangerFdStreamOf100ProfilesPerSecondIsReassembledWithoutLoss) {
  RangerConfig cfg;
  cfg.node = 0x22;
  auto bus = sim_bus(true);
  ASSERT_NE(bus, nullptr);
  sim::SimRangerConfig rc;
  rc.node = 0x22;
  auto ranger = std::make_shared<sim::SimProfileRanger>(rc);
  bus->add(ranger);
  RangerCanSource driver(cfg, socket_for(ranger_filter(cfg), true));
  ASSERT_TRUE(driver.start().ok);
  bus->start();
  std::vector<hal::RangerProfile> out;
  ASSERT_TRUE(eventually(
      [&] {
        driver.read(out, 10ms);
        return out.size() >= 100;
      },
      5000ms));
  for (std::size_t i = 1; i < out.size(); ++i) EXPECT_EQ(out[i].sequence, out[i - 1].sequence + 1);
  const CanCounters c = driver.counters();
  EXPECT_EQ(c[Counter::kGaps], 0u);
  EXPECT_EQ(c[Counter::kCrcErrors], 0u);
  EXPECT_EQ(c.transport.rx_overflow, 0u);
  driver.stop();
  bus->stop();
}

TEST(CanHil, CandumpSeesOurSyncAndCansendFramesReachTheDriver) {
  const std::string itf = interface();
  Cia402Config master;
  master.joints = {{9, 1, 1e-6, 0.0}};
  master.start_nodes = false;
  std::string text;
  {
    // The driver runs until candump has seen three SYNCs (it exits by itself with -n 3).
    Cia402JointSource driver(master, socket_for(cia402_filter(master)));
    ASSERT_TRUE(driver.start().ok);
    FILE* dump = popen(("timeout 20 candump -n 3 " + itf + ",080:7FF").c_str(), "r");
    ASSERT_NE(dump, nullptr);
    char line[256];
    while (fgets(line, sizeof(line), dump)) text += line;
    EXPECT_EQ(pclose(dump), 0);
  }
  // Three consecutive SYNCs with a one-byte counter.
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << text;
  EXPECT_NE(text.find("080   [1]"), std::string::npos) << text;

  Cia402Config follower;
  follower.sync_master = false;
  follower.start_nodes = false;
  follower.joints = {{5, 1, 1e-6, 0.0}};
  Cia402JointSource driver(follower, socket_for(cia402_filter(follower)));
  ASSERT_TRUE(driver.start().ok);
  std::this_thread::sleep_for(50ms);
  EXPECT_TRUE(cansend("080#01") && cansend("185#370640420F00"));
  std::vector<hal::JointSample> out;
  ASSERT_TRUE(eventually([&] {
    driver.read(out, 10ms);
    return !out.empty();
  }));
  EXPECT_NEAR(out[0].angle_rad, 1.0, 1e-9);  // 0x000F4240 increments * 1e-6
  EXPECT_EQ(out[0].status, 0x0637);
}

}  // namespace can_hil_test
}  // namespace rangefit::drivers::can
