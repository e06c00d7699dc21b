#pragma once
// Exact ground truth for the CSS assembler without the simulator: a plane in the world frame,
// the robot's last joint turning at a constant rate, and CssGeometry's rays intersected with the
// plane at every sample's instant (stamp + i * period / 512).

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "fusion/css_assembler.hpp"
#include "hal/css_geometry.hpp"
#include "hal/samples.hpp"

namespace rangefit::fusion::testing {

struct CssTruthScan {
  std::vector<hal::CssRevolution> revolutions;
  std::vector<hal::JointSample> joints;
  std::vector<std::vector<Eigen::Vector3d>> hits;  // [revolution][sample]; NaN when no return
  double omega_rate_rad_s = 0.0;
  hal::Timestamp t_start{};  // omega = -delta
  hal::Timestamp t_end{};    // omega = +delta
};

struct CssTruthOptions {
  int revolutions = 20;
  hal::Timestamp t0 = std::chrono::seconds(100);
  hal::Duration period = std::chrono::nanoseconds(1'000'000'000 / 7);
  double speed_mm_s = 2.0;  // v of eq. 4.21
  hal::Duration joint_period = std::chrono::milliseconds(10);
  hal::Duration joint_jitter = {};  // uniform in [-jitter, +jitter] on the joint stamps
  std::uint32_t seed = 7;
  Eigen::Vector3d plane_normal = Eigen::Vector3d(0.1, 0.05, 1.0).normalized();
  double plane_offset_mm = 280.0;  // plane: n . x = offset
};

// omega(t) = -delta + rate * (t - t0), rate = v / R (eq. 4.21); joint angle = omega + omega_zero.
inline CssTruthScan make_css_truth(const CssFusionConfig& config, const CssTruthOptions& o) {
  const hal::CssGeometry& g = config.geometry;
  CssTruthScan s;
  s.omega_rate_rad_s = o.speed_mm_s / g.pivot_radius_mm;
  const auto omega_at = [&](hal::Timestamp t) {
    return -config.deflection_rad +
           s.omega_rate_rad_s * static_cast<double>((t - o.t0).count()) * 1e-9;
  };
  s.t_start = o.t0;
  s.t_end =
      o.t0 + hal::Duration(std::llround(2.0 * config.deflection_rad / s.omega_rate_rad_s * 1e9));
  constexpr int kN = hal::CssRevolution::kSamples;
  for (int r = 0; r < o.revolutions; ++r) {
    hal::CssRevolution rev;
    rev.sequence = static_cast<std::uint32_t>(r + 1);
    rev.stamp = o.t0 + o.period * r;
    rev.period = o.period;
    std::vector<Eigen::Vector3d> hits(kN, Eigen::Vector3d::Constant(std::nan("")));
    for (int i = 0; i < kN; ++i) {
      const double t_ns = static_cast<double>((rev.stamp - o.t0).count()) +
                          static_cast<double>(o.period.count()) * i / kN;
      const double omega = -config.deflection_rad + s.omega_rate_rad_s * t_ns * 1e-9;
      const Eigen::Isometry3d T = g.T_world_css(omega);
      const Eigen::Vector3d origin = T * g.laser_point();
      const Eigen::Vector3d dir = T.linear() * g.beam_direction(g.beam_angle(i, kN));
      const double denom = o.plane_normal.dot(dir);
      const double range = (o.plane_offset_mm - o.plane_normal.dot(origin)) / denom;
      if (!(range >= g.min_range_mm && range <= g.max_range_mm)) {
        rev.range_mm[i] = hal::kNoReturn;
        continue;
      }
      rev.range_mm[i] = static_cast<float>(range);
      hits[i] = origin + range * dir;  // exact hit; the float range adds < 1e-5 mm
    }
    s.revolutions.push_back(rev);
    s.hits.push_back(std::move(hits));
  }
  std::mt19937 rng(o.seed);
  std::uniform_int_distribution<std::int64_t> jitter(-o.joint_jitter.count(),
                                                     o.joint_jitter.count());
  const hal::Timestamp end = o.t0 + o.period * (o.revolutions + 1);
  for (hal::Timestamp t = o.t0 - std::chrono::milliseconds(50); t <= end; t += o.joint_period) {
    hal::JointSample j;
    j.joint = config.joint;
    j.angle_rad = omega_at(t) + config.omega_zero_rad;
    j.stamp = t + hal::Duration(jitter(rng));
    s.joints.push_back(j);
  }
  return s;
}

}  // namespace rangefit::fusion::testing
