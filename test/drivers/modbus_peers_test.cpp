// Both sides checked by Modbus code this project did not write: the driver against an FHPP drive
// served by pymodbus, and mbpoll (a libmodbus-independent master's view of the registers) against
// our simulated drive. A missing peer tool fails the test with the package to install.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <sstream>

#include "test/drivers/modbus_test_rig.hpp"

namespace rangefit::test {
namespace modbus_peers_test {

const char* const kPython = "/usr/bin/python3";  // Debian's, where python3-pymodbus installs

// A peer process whose first stdout line is its greeting; it ends when its stdin closes.
class PeerProcess {
 public:
  ~PeerProcess() {
    if (pid_ <= 0) return;
    ::close(stdin_);
    ::close(stdout_);
    for (int i = 0; i < 200 && ::waitpid(pid_, nullptr, WNOHANG) == 0; ++i) {
      std::this_thread::sleep_for(5ms);
      if (i == 100) ::kill(pid_, SIGKILL);
    }
  }
  // Returns the first line printed, or "" when none came within the timeout.
  std::string start(const std::vector<std::string>& args, std::chrono::milliseconds timeout) {
    int in[2], out[2];
    if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0) return "";
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(in[0], 0);
      ::dup2(out[1], 1);
      ::execv(argv[0], argv.data());
      _exit(127);
    }
    ::close(in[0]);
    ::close(out[1]);
    stdin_ = in[1];
    stdout_ = out[0];
    std::string line;
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{stdout_, POLLIN, 0};
      if (::poll(&p, 1, 10) <= 0) continue;
      char c = 0;
      if (::read(stdout_, &c, 1) != 1) break;
      if (c == '\n') return line;
      line += c;
    }
    return line;
  }

 private:
  pid_t pid_ = -1;
  int stdin_ = -1;
  int stdout_ = -1;
};

// Starts the pymodbus FHPP drive; fails the test with a clear reason when it cannot.
int start_pymodbus_peer(PeerProcess& peer) {
  if (::access(kPython, X_OK) != 0) {
    ADD_FAILURE() << kPython << " missing: install python3 (scripts/deps.sh)";
    return 0;
  }
  const std::string script =
      std::string(RANGEFIT_SOURCE_DIR) + "/test/drivers/peers/fhpp_pymodbus_server.py";
  const std::string greeting = peer.start({kPython, script, "1000", "500"}, 10s);
  int port = 0;
  if (std::sscanf(greeting.c_str(), "PORT %d", &port) != 1) {
    ADD_FAILURE() << "pymodbus FHPP peer did not start: '" << greeting
                  << "' (needs python3-pymodbus and python3-serial-asyncio: scripts/deps.sh)";
  }
  return port;
}

std::string run_command(const std::string& cmd, int& exit_code) {
  std::string output;
  FILE* f = ::popen((cmd + " 2>&1").c_str(), "r");
  if (f == nullptr) return output;
  std::array<char, 256> buf{};
  while (std::fgets(buf.data(), buf.size(), f) != nullptr) output += buf.data();
  const int status = ::pclose(f);
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return output;
}

void test_against_pymodbus(drivers::FunctionMode functions) {
  PeerProcess peer;
  const int port = start_pymodbus_peer(peer);
  ASSERT_GT(port, 0);
  auto config = fast_axis_config(port);
  config.link.functions = functions;
  config.max_round_trip = 50ms;  // a Python peer answers in milliseconds, not microseconds
  config.link.response_timeout = 200ms;
  drivers::FhppAxis axis(config);
  ASSERT_TRUE(axis.start().ok);
  ASSERT_TRUE(wait_until([&] { return axis.health().state == hal::DeviceState::kStreaming; }, 3s))
      << joined_events(axis);
  EXPECT_NEAR(axis.latest()->position_mm, 100.0, 1e-3);  // the peer powers up at 100 mm
  ASSERT_TRUE(axis.enable().ok) << axis.health().message;
  ASSERT_TRUE(axis.home().ok) << axis.health().message;
  ASSERT_TRUE(wait_until([&] { return axis.motion_complete(); }, 3s));
  EXPECT_NEAR(axis.latest()->position_mm, 0.0, 1e-3);
  std::vector<hal::AxisSample> samples;
  axis.read(samples, 0ms);
  samples.clear();
  ASSERT_TRUE(axis.move_to(120.0, 500.0).ok) << axis.health().message;
  ASSERT_TRUE(wait_until([&] { return axis.motion_complete(); }, 3s));
  axis.read(samples, 10ms);
  ASSERT_GE(samples.size(), 5u);
  EXPECT_NEAR(samples.back().position_mm, 120.0, 1e-3);
  std::size_t between = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    EXPECT_GE(samples[i].position_mm, samples[i - 1].position_mm);
    if (samples[i].position_mm > 1.0 && samples[i].position_mm < 119.0) ++between;
  }
  EXPECT_GE(between, 2u);  // the motion was seen, not just its end
  EXPECT_EQ(axis.health().counters.timeouts, 0u) << joined_events(axis);
}

TEST(FhppAxisPeers, DriverHomesAndMovesAPymodbusFhppDriveWith0x17) {
  test_against_pymodbus(drivers::FunctionMode::kReadWrite);
}

TEST(FhppAxisPeers, DriverHomesAndMovesAPymodbusFhppDriveWith0x10And0x03) {
  test_against_pymodbus(drivers::FunctionMode::kSeparate);
}

// mbpoll -0: PDU addressing (register 0); -t 4:hex: holding registers shown in hex.
std::vector<unsigned> mbpoll_read(int port, std::string& output) {
  int rc = -1;
  output = run_command(
      "mbpoll -m tcp -a 1 -0 -r 0 -c 4 -t 4:hex -1 -o 1 -p " + std::to_string(port) + " 127.0.0.1",
      rc);
  std::vector<unsigned> regs;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    unsigned k = 0, value = 0;
    if (std::sscanf(line.c_str(), "[%u]: 0x%x", &k, &value) == 2 && k == regs.size()) {
      regs.push_back(value);
    }
  }
  if (rc != 0) regs.clear();
  return regs;
}

TEST(FhppAxisPeers, MbpollReadsAndDrivesTheSimulatedDrive) {
  int rc = -1;
  run_command("mbpoll -V", rc);
  ASSERT_EQ(rc, 0) << "mbpoll not installed: run scripts/deps.sh (Debian package mbpoll)";
  sim::SimFhppDrive drive(sim_axis_config());
  sim::SimAxisServer server(drive, {});
  ASSERT_TRUE(server.start().ok);

  std::string output;
  auto regs = mbpoll_read(server.port(), output);
  ASSERT_EQ(regs.size(), 4u) << output;
  // 100 mm = 100000 increments = 0x000186a0, low word first; SCON VLOAD+DIRECT, SPOS HALT+MC+STILL.
  EXPECT_EQ(regs[0], 0x4550u) << output;
  EXPECT_EQ(regs[2], 0x86a0u);
  EXPECT_EQ(regs[3], 0x0001u);

  // mbpoll writes the output telegram with 0x10: ENABLE+STOP+direct mode, HALT inactive.
  run_command("mbpoll -m tcp -a 1 -0 -r 0 -t 4 -1 -o 1 -p " + std::to_string(server.port()) +
                  " 127.0.0.1 323 0 0 0",
              rc);
  EXPECT_EQ(rc, 0);
  regs = mbpoll_read(server.port(), output);
  ASSERT_EQ(regs.size(), 4u) << output;
  const auto in = drivers::fhpp::decode_input(std::vector<std::uint16_t>(regs.begin(), regs.end()),
                                              drivers::fhpp::ByteOrder::kLowByteFirst);
  EXPECT_TRUE(in->scon & drivers::fhpp::kSconEnabled) << output;
  EXPECT_TRUE(in->scon & drivers::fhpp::kSconOpen) << output;
  EXPECT_EQ(in->position_inc, 100000);
}

}  // namespace modbus_peers_test
}  // namespace rangefit::test
