// rangefitd as systemd runs it: a separate process with $NOTIFY_SOCKET and $WATCHDOG_USEC,
// signalled like systemctl reload/stop would.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test/daemon/dds_test_env.hpp"
#include "test/daemon/notify_socket.hpp"

#ifdef RANGEFITD_PATH
namespace rangefitd_process_test {
namespace fs = std::filesystem;
using std::chrono::seconds;

void write_config(const fs::path& path, const fs::path& spool, std::uint32_t domain,
                  const std::string& extra) {
  std::ofstream(path) << "[service]\nbore_sensor = \"css\"\n"
                      << extra << "[dds]\ndomain_id = " << domain << "\n[spool]\ndirectory = \""
                      << spool.string()
                      << "\"\n[[devices]]\nname = \"css\"\nkind = \"css\"\ndriver = \"replay\"\n"
                      << "replay_file = \"" << (spool.parent_path() / "none.ply").string()
                      << "\"\n";
}

TEST(RangefitdProcess, NotifiesReadyWatchdogReloadRefusalAndStopping) {
  const fs::path dir = fs::temp_directory_path() / "rangefitd_process_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::uint32_t domain = rangefit::test::dds_test_domain();  // also sets CYCLONEDDS_URI
  const fs::path config = dir / "rangefitd.toml";
  write_config(config, dir / "spool", domain, "");
  rangefit::test::NotifySocket sock(dir / "notify.sock");
  ASSERT_TRUE(sock.ok());

  // Everything the child needs is prepared before fork(): only execve runs in the child.
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) env_strings.emplace_back(*e);
  env_strings.push_back("NOTIFY_SOCKET=" + sock.path().string());
  env_strings.push_back("WATCHDOG_USEC=200000");
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);  // slot for WATCHDOG_PID, filled in the child below
  envp.push_back(nullptr);
  std::string config_arg = config.string();
  char* argv[] = {const_cast<char*>("rangefitd"), const_cast<char*>("--config"), config_arg.data(),
                  nullptr};
  char pid_buf[64];
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // snprintf is not formally async-signal-safe but allocates nothing; glibc's is fine here.
    std::snprintf(pid_buf, sizeof pid_buf, "WATCHDOG_PID=%d", static_cast<int>(getpid()));
    envp[envp.size() - 2] = pid_buf;
    execve(RANGEFITD_PATH, argv, envp.data());
    _exit(127);
  }
  EXPECT_NE(sock.wait_for("READY=1", std::chrono::milliseconds(30000)), "");
  EXPECT_NE(sock.wait_for("WATCHDOG=1", std::chrono::milliseconds(30000)), "");

  // A broken config on SIGHUP: RELOADING=1, then READY=1 with the reason; the daemon lives on.
  write_config(config, dir / "spool", domain, "queue_capacity = 0\n");
  kill(pid, SIGHUP);
  EXPECT_NE(sock.wait_for("RELOADING=1", std::chrono::milliseconds(30000)), "");
  const std::string refused = sock.wait_for("reload refused", std::chrono::milliseconds(30000));
  EXPECT_NE(refused.find("READY=1"), std::string::npos) << refused;
  EXPECT_NE(refused.find("service.queue_capacity"), std::string::npos) << refused;
  EXPECT_NE(sock.wait_for("WATCHDOG=1", std::chrono::milliseconds(30000)), "");
  // A listen address outside the unit's IPAddressAllow= is refused on reload too.
  if (std::string(RANGEFITD_IP_ADDRESS_ALLOW).find("any") == std::string::npos) {
    write_config(config, dir / "spool", domain, "[http]\nlisten = \"198.51.100.1:8080\"\n");
    kill(pid, SIGHUP);
    const std::string outside = sock.wait_for("reload refused", std::chrono::milliseconds(30000));
    EXPECT_NE(outside.find("http.listen \"198.51.100.1:8080\""), std::string::npos) << outside;
    EXPECT_NE(outside.find("IPAddressAllow"), std::string::npos) << outside;
  }

  kill(pid, SIGTERM);
  EXPECT_NE(sock.wait_for("STOPPING=1", std::chrono::milliseconds(30000)), "");
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  fs::remove_all(dir);
}

TEST(RangefitdProcess, BrokenConfigAtStartFailsWithTheFieldName) {
  const fs::path dir = fs::temp_directory_path() / "rangefitd_process_test_bad";
  fs::create_directories(dir);
  std::ofstream(dir / "bad.toml") << "[dds]\ndomain_id = -1\n";
  const std::string cmd = std::string(RANGEFITD_PATH) + " --config " + (dir / "bad.toml").string() +
                          " 2>" + (dir / "err.txt").string();
  EXPECT_NE(std::system(cmd.c_str()), 0);
  std::ifstream err(dir / "err.txt");
  const std::string text((std::istreambuf_iterator<char>(err)), {});
  EXPECT_NE(text.find("dds.domain_id"), std::string::npos) << text;
  fs::remove_all(dir);
}

// The unit drops every peer outside its IPAddressAllow=: rangefitd refuses to listen there
// (the build's default list has no "any", so every address is outside it).
TEST(RangefitdProcess, AListenAddressOutsideTheUnitsAllowListIsRefusedAtStart) {
  const fs::path dir = fs::temp_directory_path() / "rangefitd_process_test_allow";
  fs::create_directories(dir);
  std::ofstream(dir / "wide.toml") << "[http]\nlisten = \"0.0.0.0:0\"\n";
  const std::string cmd = std::string(RANGEFITD_PATH) + " --config " +
                          (dir / "wide.toml").string() + " 2>" + (dir / "err.txt").string();
  const bool any = std::string(RANGEFITD_IP_ADDRESS_ALLOW).find("any") != std::string::npos;
  if (any) GTEST_SKIP() << "this build's IPAddressAllow= is " << RANGEFITD_IP_ADDRESS_ALLOW;
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::ifstream err(dir / "err.txt");
  const std::string text((std::istreambuf_iterator<char>(err)), {});
  EXPECT_NE(text.find("http.listen \"0.0.0.0:0\""), std::string::npos) << text;
  EXPECT_NE(text.find(RANGEFITD_IP_ADDRESS_ALLOW), std::string::npos) << text;
  fs::remove_all(dir);
}

}  // namespace rangefitd_process_test
#endif
