#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>

#include "drivers/usb/css_usb_driver.hpp"
#include "test/drivers/usb_fake_transport.hpp"

namespace rangefit::drivers::css_usb {
namespace usb_css_driver_test {

using std::chrono::milliseconds;
using test::FakeCssDevice;

// Polls until `done` holds (bounded, so a broken driver fails instead of hanging).
bool wait_for(const std::function<bool()>& done) {
  for (int i = 0; i < 1000 && !done(); ++i) std::this_thread::sleep_for(milliseconds(5));
  return done();
}

struct Rig {
  explicit Rig(double drift_ppm = 50.0) {
    auto transport = std::make_unique<FakeCssDevice>(7.2e9, drift_ppm, milliseconds(4));
    device = transport.get();
    CssUsbOptions options;
    options.sync_interval = milliseconds(50);
    options.retry_min = milliseconds(10);
    options.retry_max = milliseconds(40);
    options.clock.min_fit_span = milliseconds(100);
    driver = std::make_unique<CssUsbDriver>(std::move(transport), options);
  }
  // Reads until n revolutions have arrived (or the wait bound is hit).
  std::vector<hal::CssRevolution> collect(std::size_t n) {
    std::vector<hal::CssRevolution> out;
    for (int i = 0; i < 400 && out.size() < n; ++i) driver->read(out, milliseconds(10));
    return out;
  }
  FakeCssDevice* device = nullptr;
  std::unique_ptr<CssUsbDriver> driver;
};

TEST(CssUsbDriver, NothingIsReadBeforeStart) {
  Rig rig;
  std::vector<hal::CssRevolution> out;
  EXPECT_EQ(rig.driver->read(out, milliseconds(1)), 0u);
  EXPECT_EQ(rig.driver->health().state, hal::DeviceState::kDisconnected);
  EXPECT_EQ(rig.driver->health().hardware_id, "") << "no serial before the device answered";
}

TEST(CssUsbDriver, StreamsCompleteRevolutionsWithTranslatedStamps) {
  Rig rig;
  ASSERT_TRUE(rig.driver->start());
  const auto revolutions = rig.collect(60);
  ASSERT_GE(revolutions.size(), 60u);
  EXPECT_EQ(rig.driver->info()->serial, "FAKE-1");
  EXPECT_EQ(rig.driver->health().hardware_id, "FAKE-1") << "diagnostics name the device by it";
  double worst_us = 0;
  for (std::size_t k = 0; k < revolutions.size(); ++k) {
    const hal::CssRevolution& r = revolutions[k];
    EXPECT_EQ(r.sequence, revolutions[0].sequence + k);
    EXPECT_FLOAT_EQ(r.range_mm[100], range_mm(FakeCssDevice::pattern(r.sequence, 100)));
    EXPECT_EQ(r.quality[3], 2);
    worst_us = std::max(
        worst_us,
        std::abs(static_cast<double>((r.stamp - rig.device->truth(r.sequence)).count())) / 1e3);
  }
  // Translated through GET_TIME, not the completion time (which lags by a whole period, 4 ms).
  EXPECT_LT(worst_us, 1000.0);
  EXPECT_EQ(rig.driver->host_stamped(), 0u);
  EXPECT_EQ(rig.driver->health().state, hal::DeviceState::kStreaming);
  EXPECT_EQ(rig.driver->health().counters.gaps, 0u);
  rig.driver->stop();
  EXPECT_EQ(rig.driver->health().state, hal::DeviceState::kDisconnected);
}

TEST(CssUsbDriver, AbsentAtStartThenPluggedInStartsStreaming) {
  Rig rig;
  rig.device->set_present(false);
  ASSERT_TRUE(rig.driver->start());
  std::this_thread::sleep_for(milliseconds(60));  // several failed opens with back-off
  EXPECT_EQ(rig.driver->health().state, hal::DeviceState::kDisconnected);
  rig.device->set_present(true);
  EXPECT_GE(rig.collect(5).size(), 5u);
  EXPECT_EQ(rig.driver->health().counters.reconnects, 0u);
}

TEST(CssUsbDriver, UnplugIsReportedAndReplugResumes) {
  Rig rig;
  ASSERT_TRUE(rig.driver->start());
  ASSERT_GE(rig.collect(10).size(), 10u);
  rig.device->set_present(false);
  ASSERT_TRUE(
      wait_for([&] { return rig.driver->health().state == hal::DeviceState::kDisconnected; }));
  EXPECT_NE(rig.driver->health().message.find("scan incomplete"), std::string::npos);
  rig.device->set_present(true);
  ASSERT_TRUE(wait_for([&] { return rig.driver->health().state == hal::DeviceState::kStreaming; }));
  std::vector<hal::CssRevolution> drained;
  rig.driver->read(drained, milliseconds(0));
  EXPECT_GE(rig.collect(10).size(), 10u);
  EXPECT_EQ(rig.driver->health().counters.reconnects, 1u);
  EXPECT_GE(rig.device->opens(), 2);
}

TEST(CssUsbDriver, CorruptFramesGapsStallsAndShortTransfersAreCounted) {
  Rig rig;
  rig.device->split_transfers(true);
  ASSERT_TRUE(rig.driver->start());
  ASSERT_GE(rig.collect(5).size(), 5u);
  rig.device->corrupt_next();
  ASSERT_TRUE(wait_for([&] { return rig.driver->health().counters.crc_errors == 1; }));
  rig.device->skip_next();
  ASSERT_TRUE(
      wait_for([&] { return rig.driver->health().counters.gaps == 2; }));  // + the corrupt one
  rig.device->stall_next();
  ASSERT_TRUE(wait_for([&] { return rig.driver->health().counters.timeouts == 1; }));
  const std::uint64_t before = rig.driver->health().counters.samples;
  ASSERT_TRUE(wait_for([&] { return rig.driver->health().counters.samples > before + 5; }));
  EXPECT_EQ(rig.driver->health().state, hal::DeviceState::kStreaming);
}

}  // namespace usb_css_driver_test
}  // namespace rangefit::drivers::css_usb
