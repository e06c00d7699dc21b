#include "test/hil/cell_peer/stripe_profiles.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <numbers>
#include <sstream>

#include "drivers/can/ranger_codec.hpp"
#include "sim/ranger_simulator.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scene.hpp"
#include "sim/scene_loader.hpp"

namespace rangefit::hil {
namespace {

// First line of a recording; the ranges follow as little-endian U16 (test equipment of x86 hosts).
constexpr const char* kMagic = "rangefit-stripe-profiles";
constexpr int kVersion = 2;  // 2: the first coordinate in the header

}  // namespace

ProfileSweep stripe_cell_sweep(const hal::StripeCellGeometry& g) {
  ProfileSweep s;
  s.ranger = g.ranger;
  s.start = 0.0;
  s.step = 0.05;
  s.count = static_cast<std::size_t>(std::floor(g.axis_travel_mm / s.step)) + 1;
  s.units_um = 10;
  s.T_scene_ranger = [g](const sim::Scene& scene, double axis_mm) {
    return Eigen::Isometry3d(scene.mounts.T_scene_stripe * g.T_world_ranger(axis_mm));
  };
  return s;
}

ProfileSweep pan_tilt_sweep(const hal::PanTiltGeometry& g, double half_rad, double tilt_rad,
                            double step_rad) {
  // A margin of 1 deg beyond both ends: the peer's head stops a little past them under load.
  const double margin = 1.0 * std::numbers::pi / 180.0;
  ProfileSweep s;
  s.ranger = g.ranger;
  s.start = g.pan_zero_rad - half_rad - margin;
  s.step = step_rad;
  s.count = static_cast<std::size_t>(std::ceil(2.0 * (half_rad + margin) / step_rad)) + 1;
  s.units_um = 50;
  s.T_scene_ranger = [g, tilt_rad](const sim::Scene& scene, double pan_rad) {
    return Eigen::Isometry3d(scene.mounts.T_scene_pantilt * g.T_world_ranger(pan_rad, tilt_rad));
  };
  return s;
}

StripeProfiles::StripeProfiles(const std::string& path, const ProfileSweep& sweep) {
  try {
    if (path.ends_with(".profiles")) {
      load(path);
    } else {
      cast(path, sweep);
    }
  } catch (const std::exception& e) {
    error_ = path + ": " + e.what();
  }
  if (!error_.empty()) ranges_.clear();
}

void StripeProfiles::cast(const std::string& scene_path, const ProfileSweep& sweep) {
  const sim::Scene scene = sim::load_scene(scene_path);
  const sim::RayCaster caster(scene);
  const hal::StripeRanger& r = sweep.ranger;
  points_ = static_cast<std::size_t>(r.points_per_profile);
  start_ = sweep.start;
  step_ = sweep.step;
  units_um_ = sweep.units_um;
  const std::size_t count = sweep.count;
  ranges_.assign(count * points_, drivers::can::ranger::kNoReturn);
  const double unit_mm = units_um_ / 1000.0;
  for (std::size_t j = 0; j < count; ++j) {
    const Eigen::Isometry3d T_scene_ranger =
        sweep.T_scene_ranger(scene, start_ + static_cast<double>(j) * step_);
    const sim::ProfileTruth t = sim::cast_profile(caster, r, T_scene_ranger);
    for (int k = 0; k < r.points_per_profile; ++k) {
      const auto i = static_cast<std::size_t>(k);
      double x = t.x_mm[i], z = t.z_mm[i];
      if (std::isnan(z)) continue;
      sim::quantise_to_chip(r, k, x, z);  // as the simulated ranger (sim/ranger_simulator.cpp)
      const long raw = std::lround(z / unit_mm);
      if (!r.depth_in_range(z) || raw < 0 || raw >= drivers::can::ranger::kNoReturn) continue;
      ranges_[j * points_ + i] = static_cast<std::uint16_t>(raw);
    }
  }
}

void StripeProfiles::load(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::string line;
  if (!std::getline(f, line)) {
    error_ = "missing or empty recording";
    return;
  }
  std::istringstream head(line);
  std::string magic;
  int version = 0, units = 0;
  std::size_t count = 0;
  head >> magic >> version >> points_ >> count >> start_ >> step_ >> units;
  if (!head || magic != kMagic || version != kVersion || points_ == 0 ||
      points_ > drivers::can::ranger::kMaxPoints || count == 0 || !(step_ > 0.0) || units < 1 ||
      units > 255) {
    error_ = "not a stripe profile recording (header \"" + line + "\")";
    return;
  }
  units_um_ = static_cast<std::uint8_t>(units);
  ranges_.resize(count * points_);
  const auto bytes = static_cast<std::streamsize>(ranges_.size() * sizeof(std::uint16_t));
  if (!f.read(reinterpret_cast<char*>(ranges_.data()), bytes)) {
    error_ = "recording is truncated (" + std::to_string(count) + " profiles announced)";
  }
}

bool StripeProfiles::save(const std::string& path) const {
  std::ofstream f(path, std::ios::binary);
  f.precision(17);
  f << kMagic << ' ' << kVersion << ' ' << points_ << ' ' << size() << ' ' << start_ << ' ' << step_
    << ' ' << static_cast<int>(units_um_) << '\n';
  f.write(reinterpret_cast<const char*>(ranges_.data()),
          static_cast<std::streamsize>(ranges_.size() * sizeof(std::uint16_t)));
  return static_cast<bool>(f);
}

void StripeProfiles::fill(double coordinate, std::span<std::uint16_t> out) const {
  if (size() == 0) {
    std::fill(out.begin(), out.end(), drivers::can::ranger::kNoReturn);
    return;
  }
  const double j =
      std::clamp(std::round((coordinate - start_) / step_), 0.0, static_cast<double>(size() - 1));
  const std::uint16_t* profile = ranges_.data() + static_cast<std::size_t>(j) * points_;
  std::copy_n(profile, std::min(out.size(), points_), out.begin());
}

sim::SimRangerConfig ranger_config(const StripeProfiles& profiles, std::uint8_t node,
                                   double rate_hz) {
  sim::SimRangerConfig rc;
  rc.node = node;
  rc.rate_hz = rate_hz;
  rc.points = static_cast<std::uint16_t>(profiles.points());
  rc.units_um = profiles.units_um();
  return rc;
}

}  // namespace rangefit::hil
