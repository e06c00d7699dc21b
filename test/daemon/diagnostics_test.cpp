// REP 107 statuses as a ROS user reads them: one per device, named after the configured device,
// its hardware_id the device's own serial once the device has told it (so a swapped sensor shows
// in the diagnostics), and a rate from the sample counter between two builds.
#include "daemon/service/diagnostics.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace rangefit::daemon {
namespace diagnostics_test {

using std::chrono::seconds;

const DiagStatus* find(const std::vector<DiagStatus>& all, const std::string& name) {
  for (const auto& s : all) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::string value(const DiagStatus& s, const std::string& key) {
  for (const auto& [k, v] : s.values) {
    if (k == key) return v;
  }
  return "<none>";
}

TEST(Diagnostics, HardwareIdIsTheDevicesSerialOnceKnownElseItsName) {
  hal::DeviceHealth css;
  css.state = hal::DeviceState::kStreaming;
  css.hardware_id = "OST-0042";
  css.counters.samples = 100;
  hal::DeviceHealth axis;  // absent: no serial yet
  DiagnosticsBuilder builder;
  const auto first = builder.build({{"css", css}, {"axis", axis}}, {}, hal::Timestamp(seconds(1)));
  const DiagStatus* c = find(first, "rangefitd: device css");
  const DiagStatus* a = find(first, "rangefitd: device axis");
  ASSERT_TRUE(c && a);
  EXPECT_EQ(c->hardware_id, "OST-0042");
  EXPECT_EQ(c->level, kDiagOk);
  EXPECT_EQ(a->hardware_id, "axis");
  EXPECT_EQ(a->level, kDiagError);
  ASSERT_NE(find(first, "rangefitd: pipeline"), nullptr);

  css.counters.samples = 170;  // 70 revolutions in 10 s
  const auto second =
      builder.build({{"css", css}, {"axis", axis}}, {}, hal::Timestamp(seconds(11)));
  EXPECT_EQ(value(*find(second, "rangefitd: device css"), "rate_hz"), "7.0");
}

}  // namespace diagnostics_test
}  // namespace rangefit::daemon
