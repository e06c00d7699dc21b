#pragma once
// DDS in tests: loopback-only Cyclone configuration and a domain id of this process's own, so
// parallel test runs (and other engineers' daemons) never see each other.
//
// The id is reserved, not drawn: a random id among 200 collided with another test process often
// enough over a long run that a daemon of another test (with another configuration) answered
// this test's requests. Each process holds an exclusive flock on <tmp>/rangefit-dds-domain-N.lock
// for the id it uses until it exits (the kernel drops the lock with the process, even on a
// crash), and the next process takes the next free id.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

namespace rangefit::test {

inline constexpr std::uint32_t kTestDomains = 200;  // ids 1 .. 200

// A DDS domain id no other process on this machine holds; held until this process exits, or
// until *lock_fd (when given) is closed.
inline std::uint32_t reserve_dds_domain(int* lock_fd = nullptr) {
  const std::uint32_t first = std::random_device{}() % kTestDomains;
  const std::filesystem::path tmp = std::filesystem::temp_directory_path();
  for (std::uint32_t i = 0; i < kTestDomains; ++i) {
    const std::uint32_t domain = 1 + (first + i) % kTestDomains;
    const std::string lock = (tmp / ("rangefit-dds-domain-" + std::to_string(domain) + ".lock"));
    const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {  // fd stays open: the reservation
      if (lock_fd != nullptr) *lock_fd = fd;
      return domain;
    }
    ::close(fd);
  }
  if (lock_fd != nullptr) *lock_fd = -1;
  return 1 + first;  // every id held: share one rather than fail
}

// Points CYCLONEDDS_URI at the loopback configuration and returns this process's domain id.
inline std::uint32_t dds_test_domain() {
  static const std::uint32_t domain = [] {
    const std::string uri =
        std::string("file://") + RANGEFIT_SOURCE_DIR + "/systemd/cyclonedds-loopback.xml";
    setenv("CYCLONEDDS_URI", uri.c_str(), 1);
    return reserve_dds_domain();
  }();
  return domain;
}

}  // namespace rangefit::test
