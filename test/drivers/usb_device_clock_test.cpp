#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "drivers/usb/device_clock.hpp"

namespace rangefit::drivers::css_usb {
namespace usb_device_clock_test {

using std::chrono::microseconds;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

// A device whose us counter runs `drift_ppm` fast with an arbitrary offset, optionally wrapping;
// USB round trips have a fixed latency plus exponential jitter in each direction.
class SimulatedDevice {
 public:
  SimulatedDevice(double offset_us, double drift_ppm, int counter_bits, std::uint32_t seed)
      : offset_us_(offset_us), rate_(1.0 + drift_ppm * 1e-6), bits_(counter_bits), rng_(seed) {}

  std::uint64_t counter_at(hal::Timestamp host) const {
    const double us = offset_us_ + static_cast<double>(host.count()) / 1e3 * rate_;
    const auto ticks = static_cast<std::uint64_t>(std::floor(us));
    return bits_ >= 64 ? ticks : ticks & ((std::uint64_t{1} << bits_) - 1);
  }

  // One GET_TIME exchange starting at host time t; returns (before, device, after).
  void exchange(DeviceClock& clock, hal::Timestamp t) {
    std::exponential_distribution<double> jitter(1.0 / 100e3);  // mean 100 us, in ns
    const hal::Timestamp read_at =
        t + nanoseconds(40'000 + static_cast<std::int64_t>(jitter(rng_)));
    const hal::Timestamp after =
        read_at + nanoseconds(40'000 + static_cast<std::int64_t>(jitter(rng_)));
    clock.add_exchange(t, counter_at(read_at), after);
  }

 private:
  double offset_us_;
  double rate_;
  int bits_;
  std::mt19937 rng_;
};

// Syncs in bursts of 4 every 500 ms for `seconds`, then checks revolution stamps (7 Hz) over
// the next second; returns the worst error.
double worst_error_after(DeviceClock& clock, SimulatedDevice& device, double seconds) {
  const hal::Timestamp start = std::chrono::hours(30);  // the host has been up a while
  hal::Timestamp t = start;
  for (; t < start + nanoseconds(static_cast<std::int64_t>(seconds * 1e9));
       t += milliseconds(500)) {
    for (int k = 0; k < 4; ++k) device.exchange(clock, t + milliseconds(k));
  }
  double worst = 0;
  for (hal::Timestamp truth = t; truth < t + std::chrono::seconds(1);
       truth += microseconds(142857)) {
    const auto host = clock.to_host(device.counter_at(truth));
    EXPECT_TRUE(host);
    worst = std::max(worst, std::abs(static_cast<double>((*host - truth).count())) / 1e3);
  }
  return worst;
}

TEST(DeviceClock, UnsynchronisedClockTranslatesNothing) {
  DeviceClock clock;
  EXPECT_FALSE(clock.synchronised());
  EXPECT_FALSE(clock.to_host(12345));
}

TEST(DeviceClock, OffsetAnd50PpmDriftGiveStampsWithin20UsAfter10S) {
  DeviceClock clock;
  SimulatedDevice device(-7.5e9, 50.0, 64, 1);
  EXPECT_LT(worst_error_after(clock, device, 10.0), 20.0);
  EXPECT_NEAR(clock.drift_ppm(), 50.0, 5.0);
}

TEST(DeviceClock, WithoutDriftTrackingTheSameDeviceWouldBeFarOff) {
  // The same scenario with drift tracking disabled (fit span never reached): the error after
  // 10 s is dominated by 50 ppm x (time since the first exchange), showing the test can fail.
  ClockOptions options;
  options.min_fit_span = std::chrono::hours(1);
  DeviceClock clock(options);
  SimulatedDevice device(-7.5e9, 50.0, 64, 1);
  EXPECT_GT(worst_error_after(clock, device, 10.0), 100.0);
}

TEST(DeviceClock, NegativeDriftAndA32BitCounterWrap) {
  ClockOptions options;
  options.counter_bits = 32;  // wraps every 71.6 min; start 3 s before the wrap
  DeviceClock clock(options);
  const double start_us = 30.0 * 3600e6;  // host time of the scan start, us
  const double rate = 1.0 - 80e-6;
  SimulatedDevice device(4294967296.0 - 3e6 - start_us * rate, -80.0, 32, 2);
  EXPECT_LT(worst_error_after(clock, device, 10.0), 20.0);
  EXPECT_NEAR(clock.drift_ppm(), -80.0, 5.0);
}

TEST(DeviceClock, SlowExchangesAreRejectedAndResetForgets) {
  DeviceClock clock;
  const hal::Timestamp t = std::chrono::seconds(100);
  EXPECT_FALSE(clock.add_exchange(t, 5, t + milliseconds(50)));
  EXPECT_FALSE(clock.add_exchange(t, 5, t - microseconds(1)));
  EXPECT_FALSE(clock.synchronised());
  EXPECT_TRUE(clock.add_exchange(t, 5'000'000, t + microseconds(100)));
  EXPECT_EQ(*clock.to_host(5'000'000), t + microseconds(50));
  EXPECT_EQ(*clock.to_host(5'001'000), t + microseconds(1050));
  clock.reset();
  EXPECT_FALSE(clock.to_host(5'000'000));
}

}  // namespace usb_device_clock_test
}  // namespace rangefit::drivers::css_usb
