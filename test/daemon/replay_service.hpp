#pragma once
// rangefitd's service in-process for the DDS tests: a configuration whose one device "css"
// replays a PLY file (driver = "replay") as the default bore sensor, on the tests' loopback DDS
// domain, spooling below the test's own folder; and the service's step loop on a thread.
#include <unistd.h>
#include <atomic>
#include <chrono>

#include <filesystem>
#include <thread>

#include "daemon/rangefitd/service.hpp"
#include "daemon/service/config.hpp"
#include "test/daemon/dds_test_env.hpp"

namespace rangefit::test {

// An empty folder for one test (what an earlier run left there is removed).
// Under the temp directory, one per process: ctest runs the cases of one test program in
// parallel processes, which must not clear each other's spool.
inline std::filesystem::path fresh_test_dir(const std::filesystem::path& relative) {
  const auto dir = std::filesystem::temp_directory_path() /
                   (relative.string() + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline daemon::DaemonConfig replay_css_config(const std::filesystem::path& dir,
                                              const std::filesystem::path& ply) {
  daemon::DaemonConfig config;
  config.dds.domain_id = dds_test_domain();
  config.spool.directory = dir / "spool";
  daemon::DeviceConfig css;
  css.name = "css";
  css.kind = "css";
  css.driver = daemon::DriverKind::kReplay;
  css.replay_file = ply;
  config.devices.push_back(css);
  config.service.bore_sensor = "css";
  return config;
}

// Steps the service on its own thread, as rangefitd's main loop does, until destroyed.
class ServiceLoop {
 public:
  explicit ServiceLoop(daemon::Service& service)
      : thread_([this, &service] {
          while (running_) service.step(std::chrono::milliseconds(20));
        }) {}
  ~ServiceLoop() {
    running_ = false;
    thread_.join();
  }
  ServiceLoop(const ServiceLoop&) = delete;
  ServiceLoop& operator=(const ServiceLoop&) = delete;

 private:
  std::atomic<bool> running_{true};  // before thread_: set when the thread starts
  std::thread thread_;
};

}  // namespace rangefit::test
