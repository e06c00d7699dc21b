// Hardware-in-the-loop: the CSS driver (LibusbTransport + CssUsbDriver) against the simulated
// sensor served as a real USB device (test/hil/css_gadget: FunctionFS on dummy_hcd) inside the qemu
// VM (test/hil/run_vm.sh loads the modules and runs udevd for hotplug). The device runs faster than
// real time by SET_RATE; its µs counter has an offset, drift and optionally 32 bits, and it keeps
// the host time of every index pulse as ground truth. Labelled `hil`: needs root and the modules.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <thread>

#include "drivers/usb/css_usb_driver.hpp"
#include "drivers/usb/libusb_transport.hpp"
#include "test/hil/css_gadget/css_gadget.hpp"

namespace rangefit::hil {
namespace usb_css_hil_test {

using namespace std::chrono_literals;
using drivers::css_usb::CssUsbDriver;
using drivers::css_usb::CssUsbOptions;
using drivers::css_usb::LibusbTransport;

bool eventually(const std::function<bool()>& done, std::chrono::milliseconds limit = 8000ms) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

double error_us(hal::Timestamp a, hal::Timestamp b) {
  return static_cast<double>((a - b).count()) / 1e3;
}

struct UsbRig {
  explicit UsbRig(CssGadgetOptions g = {}, std::uint16_t rate_centi_hz = 7000) : gadget(g) {
    CssUsbOptions o;
    o.rate_centi_hz = rate_centi_hz;  // 70 Hz: ten times real time unless a test says otherwise
    o.clock.counter_bits = g.clock.counter_bits;
    o.retry_max = 500ms;
    driver = std::make_unique<CssUsbDriver>(std::make_unique<LibusbTransport>(), o);
  }
  // Reads until `n` revolutions have arrived in total (or `limit` passes).
  bool collect(std::size_t n, std::chrono::milliseconds limit = 10000ms) {
    return eventually(
        [&] {
          driver->read(got, 10ms);
          return got.size() >= n;
        },
        limit);
  }
  hal::DeviceHealth health() const { return driver->health(); }

  CssGadget gadget;
  std::unique_ptr<CssUsbDriver> driver;
  std::vector<hal::CssRevolution> got;
};

// The samples the simulated cell measured for revolution `sequence`, exactly as decoded.
void expect_samples_of(const CssGadget& gadget, const hal::CssRevolution& r) {
  const auto& wire = gadget.source().samples(r.sequence);
  for (std::size_t i = 0; i < drivers::css_usb::kSamples; ++i) {
    const float want = drivers::css_usb::range_mm(wire[i].range_um);
    if (std::isnan(want)) {
      ASSERT_TRUE(std::isnan(r.range_mm[i])) << "revolution " << r.sequence << " sample " << i;
    } else {
      ASSERT_FLOAT_EQ(r.range_mm[i], want) << "revolution " << r.sequence << " sample " << i;
    }
    ASSERT_EQ(r.intensity[i], wire[i].intensity);
    ASSERT_EQ(r.quality[i], wire[i].quality);
  }
}

CssGadgetOptions scene_device(double offset_us, double drift_ppm) {
  CssGadgetOptions g;
  g.scene_path = RANGEFIT_HIL_CSS_SCAN;  // the bore plate's scan, recorded by the build
  g.clock.offset_us = offset_us;
  g.clock.drift_ppm = drift_ppm;
  return g;
}

TEST(UsbCssHil, FullScanOfTheSimulatedCellArrivesCompleteWithSamplesAndStamps) {
  UsbRig rig(scene_device(4.2e9, 50.0));
  ASSERT_EQ(rig.gadget.source().error(), "");
  const std::size_t scan = rig.gadget.source().size();
  ASSERT_EQ(scan, 175u);  // 25 s at 7 Hz, served at 70 Hz
  ASSERT_EQ(rig.gadget.start(), "");
  ASSERT_TRUE(rig.driver->start());
  ASSERT_TRUE(rig.collect(scan, 20000ms)) << rig.got.size() << " of " << scan;
  EXPECT_EQ(rig.driver->info()->serial, "CSS-SIM-0001");
  EXPECT_EQ(rig.gadget.rate_centi_hz(), 7000);
  double worst_us = 0.0;
  for (std::size_t k = 0; k < scan; ++k) {
    const hal::CssRevolution& r = rig.got[k];
    ASSERT_EQ(r.sequence, k);
    expect_samples_of(rig.gadget, r);
    worst_us = std::max(worst_us, std::abs(error_us(r.stamp, *rig.gadget.truth(r.sequence))));
    EXPECT_NEAR(static_cast<double>(r.period.count()) / 1e3, 14286.0, 2.0);
  }
  // Stamps come from the device clock (the drift fit needs 5 s: nominal rate here): the transfer
  // completion would be a period (14 ms) late. 2 ms allows slow first exchanges on a loaded host.
  EXPECT_LT(worst_us, 2000.0);
  EXPECT_EQ(rig.driver->host_stamped(), 0u);
  const hal::DeviceHealth h = rig.health();
  EXPECT_EQ(h.state, hal::DeviceState::kStreaming);
  EXPECT_EQ(h.counters.gaps + h.counters.crc_errors + h.counters.resyncs + h.counters.timeouts +
                h.counters.dropped + h.counters.faults,
            0u);
  std::printf("[ info ] 175 revolutions, worst stamp error %.1f us\n", worst_us);
}

TEST(UsbCssHil, AbsentAtStartThenUnplugMidScanIsReportedAndReplugResumes) {
  UsbRig rig(scene_device(1.0e6, -30.0));
  ASSERT_TRUE(rig.driver->start());  // nothing bound yet: the driver keeps retrying
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(rig.health().state, hal::DeviceState::kDisconnected);
  ASSERT_EQ(rig.gadget.start(), "");
  ASSERT_TRUE(rig.collect(20));
  ASSERT_TRUE(rig.gadget.unplug());
  ASSERT_TRUE(eventually([&] { return rig.health().state == hal::DeviceState::kDisconnected; }));
  EXPECT_NE(rig.health().message.find("scan incomplete"), std::string::npos)
      << rig.health().message;
  rig.driver->read(rig.got, 50ms);
  const std::uint32_t last = rig.got.back().sequence;
  rig.got.clear();
  ASSERT_TRUE(rig.gadget.replug());
  ASSERT_TRUE(rig.collect(20)) << rig.health().message;
  EXPECT_EQ(rig.health().state, hal::DeviceState::kStreaming);
  EXPECT_EQ(rig.health().message.find("scan incomplete"), std::string::npos);
  EXPECT_EQ(rig.health().counters.reconnects, 1u);
  EXPECT_EQ(rig.gadget.starts(), 2u);
  EXPECT_GT(rig.got.front().sequence, last);
  for (std::size_t k = 1; k < rig.got.size(); ++k) {
    EXPECT_EQ(rig.got[k].sequence, rig.got[k - 1].sequence + 1);
    expect_samples_of(rig.gadget, rig.got[k]);
  }
}

TEST(UsbCssHil, StallsShortTransfersBadCrcAndGapsAreCountedWhileStreamingGoesOn) {
  UsbRig rig;
  ASSERT_EQ(rig.gadget.start(), "");
  ASSERT_TRUE(rig.driver->start());
  ASSERT_TRUE(rig.collect(10));
  auto after = [&](Fault fault) {
    const hal::DeviceHealth before = rig.health();
    rig.gadget.inject(fault);
    const std::size_t n = rig.got.size();
    EXPECT_TRUE(rig.collect(n + 8)) << "streaming stopped after a fault";
    hal::DeviceHealth d = rig.health();
    d.counters.gaps -= before.counters.gaps;
    d.counters.crc_errors -= before.counters.crc_errors;
    d.counters.resyncs -= before.counters.resyncs;
    d.counters.timeouts -= before.counters.timeouts;
    return d.counters;
  };
  auto c = after(Fault::kBadCrc);  // that revolution is dropped and counted
  EXPECT_EQ(c.crc_errors, 1u);
  EXPECT_EQ(c.gaps, 1u);
  c = after(Fault::kGap);
  EXPECT_EQ(c.gaps, 1u);
  EXPECT_EQ(c.crc_errors, 0u);
  c = after(Fault::kTruncate);  // a 1000-byte short transfer: the revolution is lost
  EXPECT_EQ(c.gaps, 1u);
  EXPECT_GE(c.resyncs, 1u);
  c = after(Fault::kSplit);  // two short transfers of one frame: reassembled, nothing lost
  EXPECT_EQ(c.gaps, 0u);
  EXPECT_EQ(c.crc_errors, 0u);
  c = after(Fault::kStall);  // halt cleared by the driver, nothing lost
  EXPECT_GE(c.timeouts, 1u);
  EXPECT_EQ(c.gaps, 0u);
  EXPECT_EQ(rig.health().state, hal::DeviceState::kStreaming);
  for (const hal::CssRevolution& r : rig.got) expect_samples_of(rig.gadget, r);
}

TEST(UsbCssHil, DeviceCounterWrappingAt2To32KeepsStampsContinuous) {
  CssGadgetOptions g;
  g.clock.counter_bits = 32;
  g.clock.offset_us = DeviceClockModel::offset_wrapping_after(hal::monotonic_now(), 2s, 0.0, 32);
  UsbRig rig(g);
  ASSERT_EQ(rig.gadget.start(), "");
  ASSERT_TRUE(rig.driver->start());
  const std::uint64_t before = rig.gadget.clock().read(hal::monotonic_now());
  ASSERT_TRUE(eventually([&] {
    rig.driver->read(rig.got, 5ms);  // keep the driver's queue (64 revolutions) drained
    return rig.gadget.clock().read(hal::monotonic_now()) < before;
  }));
  const std::size_t n = rig.got.size() + 70;  // another second at 70 Hz past the wrap
  ASSERT_TRUE(rig.collect(n));
  for (std::size_t k = 1; k < rig.got.size(); ++k) {
    const hal::CssRevolution& r = rig.got[k];
    EXPECT_EQ(r.sequence, rig.got[k - 1].sequence + 1);
    EXPECT_NEAR(error_us(r.stamp, rig.got[k - 1].stamp), 14286.0, 1000.0) << "at " << r.sequence;
    EXPECT_NEAR(error_us(r.stamp, *rig.gadget.truth(r.sequence)), 0.0, 1000.0);
  }
  EXPECT_EQ(rig.health().counters.gaps + rig.health().counters.dropped, 0u);
}

TEST(UsbCssHil, GetTimeReadingLiesWithinEveryExchangeWindow) {
  CssGadgetOptions g;
  g.clock.offset_us = 2.5e9;
  g.clock.drift_ppm = 50.0;
  CssGadget gadget(g);
  ASSERT_EQ(gadget.start(), "");
  LibusbTransport usb;
  ASSERT_TRUE(eventually([&] { return static_cast<bool>(usb.open()); }));
  std::vector<double> trips, asym;
  for (int k = 0; k < 100; ++k) {
    std::array<std::uint8_t, 8> reply{};
    std::size_t received = 0;
    LibusbTransport::Window window;
    if (!usb.control_in_timed(drivers::css_usb::Request::kGetTime, 0, reply, received, window)) {
      continue;  // a timeout on a loaded host; the driver drops such exchanges too
    }
    const hal::Timestamp before = window.submitted;
    const hal::Timestamp after = window.completed;
    ASSERT_EQ(received, 8u);
    std::uint64_t device = 0;
    for (int i = 7; i >= 0; --i) device = device << 8 | reply[static_cast<std::size_t>(i)];
    const hal::Timestamp truth = gadget.clock().host_time(static_cast<double>(device));
    // The device read its counter between the request leaving and the reply arriving (1 us
    // counter resolution).
    EXPECT_LE(before - 1us, truth);
    EXPECT_LE(truth, after + 1us);
    trips.push_back(error_us(after, before));
    asym.push_back(error_us(truth, before + (after - before) / 2));
  }
  ASSERT_GE(trips.size(), 50u);
  std::vector<std::size_t> order(trips.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return trips[a] < trips[b]; });
  for (std::size_t q : {std::size_t{0}, std::size_t{10}, trips.size() / 2, trips.size() - 1}) {
    std::printf("[ info ] round trip rank %zu: %.1f us, reading - midpoint %.1f us\n", q,
                trips[order[q]], asym[order[q]]);
  }
}

// The driver is specified to stay within 20 us of truth after 10 s with an offset and 50 ppm drift.
// Two-way exchanges cannot see the link's asymmetry (GetTimeReadingLiesWithinEveryExchangeWindow
// prints it: on dummy_hcd under TCG the reading sits tens of us off the midpoint, more on a loaded
// host), so here the drift must be tracked (fitted 50 +- 25 ppm: ~100 us jitter over 10 s;
// untracked: 0) and the stamps stay within half a typical round trip of the truth.
TEST(UsbCssHil, OffsetAndFiftyPpmDriftAreTrackedAfterTenSeconds) {
  UsbRig rig(scene_device(3.7e9, 50.0), 700);  // real time: the fit needs a real 10 s
  ASSERT_EQ(rig.gadget.start(), "");
  ASSERT_TRUE(rig.driver->start());
  ASSERT_TRUE(rig.collect(1, 5000ms));
  const hal::Timestamp first = rig.got.front().stamp;
  ASSERT_TRUE(eventually(
      [&] {
        rig.driver->read(rig.got, 10ms);
        return rig.got.back().stamp - first > 12s;
      },
      20000ms));
  double lo = 1e9, hi = -1e9;
  int checked = 0;
  for (const hal::CssRevolution& r : rig.got) {
    if (r.stamp - first < 10s) continue;
    const double e = error_us(r.stamp, *rig.gadget.truth(r.sequence));
    lo = std::min(lo, e);
    hi = std::max(hi, e);
    ++checked;
  }
  EXPECT_GE(checked, 10);
  EXPECT_NEAR(rig.driver->clock_drift_ppm(), 50.0, 25.0);
  EXPECT_LE(std::max(-lo, hi), 300.0);
  EXPECT_EQ(rig.driver->host_stamped(), 0u);
  std::printf("[ info ] %d revolutions after 10 s: stamp error %.1f .. %.1f us, drift %.1f ppm\n",
              checked, lo, hi, rig.driver->clock_drift_ppm());
}

}  // namespace usb_css_hil_test
}  // namespace rangefit::hil
