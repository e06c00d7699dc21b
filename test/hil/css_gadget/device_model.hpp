#pragma once
// What the simulated CSS "is", apart from USB: its free-running µs counter (offset, drift and
// counter width chosen by the test, so translation can be checked against the exact truth) and
// the revolutions it measures, cast by the simulated cell (sim::CssRig over a scene) or, without
// a scene, a synthetic pattern. Pure: no I/O after construction, no threads.

#include <cstdint>
#include <string>
#include <vector>

#include "drivers/usb/css_protocol.hpp"
#include "hal/time.hpp"

namespace rangefit::hil {

struct DeviceClockModel {
  double offset_us = 0.0;  // counter value at host CLOCK_MONOTONIC 0, before wrapping
  double drift_ppm = 0.0;  // +50: the counter gains 50 µs per host second
  int counter_bits = 64;   // the counter wraps at 2^counter_bits

  double rate() const { return 1.0 + drift_ppm * 1e-6; }
  // Unwrapped counter (µs, fractional) at a host time.
  double exact_us(hal::Timestamp host) const;
  // The counter as the device reports it: floor, wrapped to counter_bits.
  std::uint64_t read(hal::Timestamp host) const;
  // Host time at which the unwrapped counter reads `unwrapped_us` (the truth of a stamp).
  hal::Timestamp host_time(double unwrapped_us) const;
  // An offset that makes a `counter_bits` counter wrap `after` from `now`.
  static double offset_wrapping_after(hal::Timestamp now, hal::Duration after, double drift_ppm,
                                      int counter_bits);
};

// The revolutions the device measures: revolution k of the scan (k modulo the scan length).
class RevolutionSource {
 public:
  // scene_path empty: synthetic pattern (pattern()). A *.frames file: a scan recorded by save()
  // (ray casting under the VM's emulated CPU takes ~10 s, so the build records it on the host).
  // Otherwise a scene file: the simulated cell's CSS scan of it (sim::CssRig, a 25 s scan: 175
  // revolutions at 7 Hz). `error` says why a scene or recording failed (then: synthetic pattern).
  // scan_s: how long the sweep from -delta to +delta takes (the thesis' 25 s by default; a
  // faster robot gives fewer revolutions per scan).
  explicit RevolutionSource(const std::string& scene_path = "", double scan_s = 25.05);
  // Writes the scan as protocol frames (sequence = revolution index).
  bool save(const std::string& path) const;

  std::size_t size() const { return samples_.size(); }
  const std::array<drivers::css_usb::WireSample, drivers::css_usb::kSamples>& samples(
      std::uint64_t k) const {
    return samples_[k % samples_.size()];
  }
  const std::string& error() const { return error_; }
  static std::uint16_t pattern(std::uint64_t k, std::size_t i) {
    return static_cast<std::uint16_t>((k * 7 + i * 13) % 60000);
  }

 private:
  void load(const std::string& path);

  std::vector<std::array<drivers::css_usb::WireSample, drivers::css_usb::kSamples>> samples_;
  std::string error_;
};

}  // namespace rangefit::hil
