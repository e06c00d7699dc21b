#include "test/hil/cell_peer/stripe_profiles.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <sstream>

#include "drivers/can/ranger_codec.hpp"
#include "sim/ranger_simulator.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scene_loader.hpp"

namespace rangefit::hil {
namespace {

// First line of a recording; the ranges follow as little-endian U16 (test equipment of x86 hosts).
constexpr const char* kMagic = "rangefit-stripe-profiles";
constexpr int kVersion = 1;

}  // namespace

StripeProfiles::StripeProfiles(const std::string& path, StripeProfileOptions options) {
  try {
    if (path.ends_with(".profiles")) {
      load(path);
    } else {
      cast(path, options);
    }
  } catch (const std::exception& e) {
    error_ = path + ": " + e.what();
  }
  if (!error_.empty()) ranges_.clear();
}

void StripeProfiles::cast(const std::string& scene_path, const StripeProfileOptions& o) {
  const sim::Scene scene = sim::load_scene(scene_path);
  const sim::RayCaster caster(scene);
  const hal::StripeRanger& r = o.geometry.ranger;
  points_ = static_cast<std::size_t>(r.points_per_profile);
  step_mm_ = o.step_mm;
  units_um_ = o.units_um;
  const auto count =
      static_cast<std::size_t>(std::floor(o.geometry.axis_travel_mm / o.step_mm)) + 1;
  ranges_.assign(count * points_, drivers::can::ranger::kNoReturn);
  const double unit_mm = units_um_ / 1000.0;
  for (std::size_t j = 0; j < count; ++j) {
    // As sim::StripeCell: the scene rides on the table, the ranger stands in the cell.
    const Eigen::Isometry3d T_scene_ranger =
        scene.mounts.T_scene_stripe * o.geometry.T_world_ranger(static_cast<double>(j) * step_mm_);
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
  head >> magic >> version >> points_ >> count >> step_mm_ >> units;
  if (!head || magic != kMagic || version != kVersion || points_ == 0 ||
      points_ > drivers::can::ranger::kMaxPoints || count == 0 || !(step_mm_ > 0.0) || units < 1 ||
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
  f << kMagic << ' ' << kVersion << ' ' << points_ << ' ' << size() << ' ' << step_mm_ << ' '
    << static_cast<int>(units_um_) << '\n';
  f.write(reinterpret_cast<const char*>(ranges_.data()),
          static_cast<std::streamsize>(ranges_.size() * sizeof(std::uint16_t)));
  return static_cast<bool>(f);
}

void StripeProfiles::fill(double axis_mm, std::span<std::uint16_t> out) const {
  if (size() == 0) {
    std::fill(out.begin(), out.end(), drivers::can::ranger::kNoReturn);
    return;
  }
  const double j = std::clamp(std::round(axis_mm / step_mm_), 0.0, static_cast<double>(size() - 1));
  const std::uint16_t* profile = ranges_.data() + static_cast<std::size_t>(j) * points_;
  std::copy_n(profile, std::min(out.size(), points_), out.begin());
}

}  // namespace rangefit::hil
