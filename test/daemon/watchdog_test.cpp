#include <gtest/gtest.h>

#include "daemon/rangefitd/systemd_notify.hpp"
#include "test/daemon/notify_socket.hpp"

namespace rangefit::daemon {
namespace watchdog_test {

using std::chrono::seconds;

TEST(WatchdogFeeder, FeedsOnlyWhileThePipelineMakesProgress) {
  test::NotifySocket sock(std::filesystem::temp_directory_path() / "rangefit_watchdog_test.sock");
  ASSERT_TRUE(sock.ok());
  setenv("NOTIFY_SOCKET", sock.path().c_str(), 1);
  SdNotifier notifier;
  WatchdogFeeder feeder(notifier, seconds(30));
  const hal::Timestamp progress(seconds(100));
  std::string why;

  EXPECT_TRUE(feeder.tick(progress + seconds(29), progress, &why));
  EXPECT_EQ(sock.next(std::chrono::milliseconds(2000)), "WATCHDOG=1");

  EXPECT_FALSE(feeder.tick(progress + seconds(31), progress, &why));
  EXPECT_NE(why.find("no progress"), std::string::npos);
  why.clear();
  EXPECT_FALSE(feeder.tick(progress + seconds(32), progress, &why));
  EXPECT_TRUE(why.empty()) << "the stall is reported once, not every tick";
  EXPECT_EQ(sock.next(std::chrono::milliseconds(100)), "") << "a stalled pipeline is not fed";

  const hal::Timestamp resumed(seconds(140));
  EXPECT_TRUE(feeder.tick(resumed, resumed, &why));
  EXPECT_EQ(sock.next(std::chrono::milliseconds(2000)), "WATCHDOG=1");
  unsetenv("NOTIFY_SOCKET");
}

TEST(SdNotifier, WithoutANotifySocketDoesNothing) {
  unsetenv("NOTIFY_SOCKET");
  SdNotifier notifier;
  notifier.notify("READY=1");  // must not fail or block when run by hand
  EXPECT_EQ(watchdog_interval(), hal::Duration::zero());
}

}  // namespace watchdog_test
}  // namespace rangefit::daemon
