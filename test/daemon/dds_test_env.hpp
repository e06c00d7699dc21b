#pragma once
// DDS in tests: loopback-only Cyclone configuration and a random domain id per process, so
// parallel test runs (and other engineers' daemons) never see each other.
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

namespace rangefit::test {

inline std::uint32_t dds_test_domain() {
  static const std::uint32_t domain = [] {
    const std::string uri =
        std::string("file://") + RANGEFIT_SOURCE_DIR + "/systemd/cyclonedds-loopback.xml";
    setenv("CYCLONEDDS_URI", uri.c_str(), 1);
    std::random_device rd;
    return static_cast<std::uint32_t>(1 + rd() % 200);
  }();
  return domain;
}

}  // namespace rangefit::test
