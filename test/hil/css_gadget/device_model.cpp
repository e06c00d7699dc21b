#include "test/hil/css_gadget/device_model.hpp"

#include <cmath>
#include <exception>
#include <fstream>

#include "sim/css_simulator.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"

namespace rangefit::hil {

using drivers::css_usb::kSamples;
using drivers::css_usb::WireSample;

double DeviceClockModel::exact_us(hal::Timestamp host) const {
  return offset_us + rate() * static_cast<double>(host.count()) / 1e3;
}

std::uint64_t DeviceClockModel::read(hal::Timestamp host) const {
  const double us = std::floor(exact_us(host));
  const auto value = static_cast<std::uint64_t>(static_cast<std::int64_t>(us));
  if (counter_bits >= 64) return value;
  return value & ((std::uint64_t{1} << counter_bits) - 1);
}

hal::Timestamp DeviceClockModel::host_time(double unwrapped_us) const {
  return hal::Timestamp(hal::Duration(std::llround((unwrapped_us - offset_us) / rate() * 1e3)));
}

double DeviceClockModel::offset_wrapping_after(hal::Timestamp now, hal::Duration after,
                                               double drift_ppm, int counter_bits) {
  const double span = std::ldexp(1.0, counter_bits);
  const double rate = 1.0 + drift_ppm * 1e-6;
  // counter(now + after) = span  <=>  offset = span - rate * (now + after)
  return span - rate * static_cast<double>((now + after).count()) / 1e3;
}

RevolutionSource::RevolutionSource(const std::string& scene_path, double scan_s) {
  if (scene_path.ends_with(".frames")) {
    load(scene_path);
  } else if (!scene_path.empty()) {
    try {
      const sim::Scene scene = sim::load_scene(scene_path);
      const sim::RayCaster caster(scene);
      sim::SimClock clock;
      // The thesis' 25 s scan (section 4.2.1): 175 revolutions at 7 Hz, whatever the pivot radius.
      sim::CssScanOptions scan;
      scan.speed_mm_s = 2.0 * scan.deflection_rad * scan.geometry.pivot_radius_mm / scan_s;
      const sim::CssRig rig(scene, caster, scan, clock);
      samples_.resize(rig.revolutions_in_scan());
      for (std::uint64_t k = 0; k < samples_.size(); ++k) {
        const sim::CssRevolutionTruth t = rig.cast_revolution(k);
        for (std::size_t i = 0; i < kSamples; ++i) {
          const bool valid = !std::isnan(t.range_mm[i]);
          samples_[k][i] = {drivers::css_usb::range_um(static_cast<float>(t.range_mm[i])),
                            static_cast<std::uint8_t>(valid ? 200 : 0),
                            static_cast<std::uint8_t>(valid ? 255 : 0)};
        }
      }
    } catch (const std::exception& e) {
      error_ = e.what();
      samples_.clear();
    }
  }
  if (!samples_.empty()) return;
  samples_.resize(175);  // a 25 s scan at 7 Hz
  for (std::uint64_t k = 0; k < samples_.size(); ++k) {
    for (std::size_t i = 0; i < kSamples; ++i) samples_[k][i] = {pattern(k, i), 1, 2};
  }
}

void RevolutionSource::load(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::vector<std::uint8_t> frame(drivers::css_usb::kFrameBytes);
  while (
      f.read(reinterpret_cast<char*>(frame.data()), static_cast<std::streamsize>(frame.size()))) {
    const auto r = drivers::css_usb::decode_revolution(frame);
    if (!r) {
      error_ = path + ": frame " + std::to_string(samples_.size()) + " is damaged";
      samples_.clear();
      return;
    }
    samples_.push_back(r->samples);
  }
  if (samples_.empty()) error_ = path + ": no frames (missing or empty file)";
}

bool RevolutionSource::save(const std::string& path) const {
  std::ofstream f(path, std::ios::binary);
  std::vector<std::uint8_t> bytes;
  for (std::uint64_t k = 0; k < samples_.size(); ++k) {
    drivers::css_usb::WireRevolution r;
    r.sequence = static_cast<std::uint32_t>(k);
    r.samples = samples_[k];
    drivers::css_usb::encode_revolution(r, bytes);
  }
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(f);
}

}  // namespace rangefit::hil
