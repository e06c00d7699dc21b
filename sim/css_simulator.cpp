#include "sim/css_simulator.hpp"

#include <cmath>
#include <limits>

#include "sim/simulated_stream.hpp"

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;
constexpr int kN = hal::CssRevolution::kSamples;

}  // namespace

class CssRig::CssDevice final : public SimulatedStream<hal::CssRevolution> {
 public:
  CssDevice(const CssRig& rig, hal::Clock& clock)
      : SimulatedStream("sim-css", clock, rig.options_.css_faults, rig.options_.seed, 1),
        rig_(rig) {}

 protected:
  hal::Timestamp due(std::uint64_t k) const override {
    // A revolution leaves the device once complete, plus a millisecond of transfer.
    return rig_.revolution_stamp(k + 1) + std::chrono::milliseconds(1);
  }

  void make(std::uint64_t k, std::mt19937_64& rng, hal::CssRevolution& rev) override {
    const FaultOptions& f = faults();
    const hal::CssGeometry& g = rig_.options_.geometry;
    const CssRevolutionTruth truth = rig_.cast_revolution(k);
    rev.sequence = static_cast<std::uint32_t>(k);
    // The device stamps with 1 us resolution.
    rev.stamp = std::chrono::duration_cast<std::chrono::microseconds>(
        stamp_at(rig_.revolution_stamp(k), rng));
    rev.period = seconds(rig_.revolution_period_s());
    rev.flags = hal::kCssMotorLocked | hal::kCssLaserOn;
    std::normal_distribution<double> noise(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int i = 0; i < kN; ++i) {
      double r = truth.range_mm[i];
      if (!std::isnan(r) && uniform(rng) < f.ghost_probability) r = ghost_range(truth, i, r);
      if (!std::isnan(r) && f.range_noise_sigma_mm > 0.0) r += f.range_noise_sigma_mm * noise(rng);
      if (uniform(rng) < f.outlier_probability) {
        r = uniform(rng) < 0.5 ? kNaN
                               : g.min_range_mm + uniform(rng) * (g.max_range_mm - g.min_range_mm);
      }
      const bool valid = !std::isnan(r);
      rev.range_mm[i] = valid ? static_cast<float>(r) : hal::kNoReturn;
      rev.intensity[i] = valid ? 200 : 0;
      rev.quality[i] = valid ? 255 : 0;
    }
  }

 private:
  // Specular ghost: the beam mirrors off the surface and the sensor triangulates the spot it
  // lights next, which appears along the beam at the length of the mirrored path.
  double ghost_range(const CssRevolutionTruth& truth, int i, double range) const {
    const Vector3d& p = truth.point_scene[i];
    const Vector3d& n = truth.normal_scene[i];
    const Vector3d in =
        (p - rig_.T_scene_world_ * rig_.options_.geometry.T_world_css(truth.omega_rad[i]) *
                 rig_.options_.geometry.laser_point())
            .normalized();
    const Vector3d out = in - 2.0 * in.dot(n) * n;
    const Hit h = rig_.caster_.cast(Ray{p, out, kSurfaceEps, rig_.options_.geometry.max_range_mm});
    const double total = h.valid ? range + h.t : kNaN;
    return total <= rig_.options_.geometry.max_range_mm ? total : kNaN;
  }

  const CssRig& rig_;
};

class CssRig::JointDevice final : public PolledStream<hal::JointSample> {
 public:
  JointDevice(const CssRig& rig, hal::Clock& clock)
      : PolledStream("sim-robot-joint", clock, rig.options_.joint_faults, rig.options_.seed, 2,
                     rig.start_, rig.options_.joint_rate_hz),
        rig_(rig) {}

 protected:
  void fill(hal::Timestamp t, hal::Timestamp read_at, hal::JointSample& s) override {
    s.joint = rig_.options_.joint_id;
    s.angle_rad = rig_.omega_at(read_at);
    const bool moving = t >= rig_.start_ && t < rig_.scan_end();
    s.velocity_rad_s =
        moving ? rig_.options_.speed_mm_s / rig_.options_.geometry.pivot_radius_mm : 0.0;
    s.status = 0x0237;  // CiA 402 "operation enabled"
    s.valid = true;
  }

 private:
  const CssRig& rig_;
};

CssRig::CssRig(const Scene& scene, const RayCaster& caster, CssScanOptions options,
               hal::Clock& clock)
    : caster_(caster),
      options_(options),
      T_scene_world_(options.T_scene_world.value_or(scene.mounts.T_scene_css)),
      start_(clock.now()),
      css_(std::make_unique<CssDevice>(*this, clock)),
      joint_(std::make_unique<JointDevice>(*this, clock)) {}

CssRig::~CssRig() = default;

hal::CssSource& CssRig::css() { return *css_; }
hal::JointSource& CssRig::joint() { return *joint_; }

hal::Timestamp CssRig::scan_end() const {
  // Eq. 4.21: the path of 2 delta R is travelled at v.
  return start_ + seconds(2.0 * options_.deflection_rad * options_.geometry.pivot_radius_mm /
                          options_.speed_mm_s);
}

std::uint64_t CssRig::revolutions_in_scan() const {
  const double scan_s = static_cast<double>((scan_end() - start_).count()) * 1e-9;
  return static_cast<std::uint64_t>(std::floor(scan_s * options_.rotation_hz));
}

double CssRig::omega_at(hal::Timestamp t) const {
  const double dt = static_cast<double>((t - start_).count()) * 1e-9;
  const double omega =
      -options_.deflection_rad + options_.speed_mm_s / options_.geometry.pivot_radius_mm * dt;
  return std::clamp(omega, -options_.deflection_rad, options_.deflection_rad);
}

hal::Timestamp CssRig::revolution_stamp(std::uint64_t k) const {
  // The device stamps revolutions with 1 us resolution (thesis 4.2.1); its samples follow from
  // that stamp, so fusion can reproduce the beam's exact timing from the stream.
  return std::chrono::duration_cast<std::chrono::microseconds>(
      tick(start_, options_.rotation_hz, k));
}

CssRevolutionTruth CssRig::cast_revolution(std::uint64_t k) const {
  const hal::CssGeometry& g = options_.geometry;
  CssRevolutionTruth truth;
  std::array<Ray, kN> rays;
  std::array<Vector3d, kN> ccd;
  const double period_s = revolution_period_s();
  const hal::Timestamp stamp = revolution_stamp(k);
  for (int i = 0; i < kN; ++i) {
    const hal::Timestamp t = stamp + seconds(period_s * i / kN);
    const double omega = omega_at(t);
    const Eigen::Isometry3d T = T_scene_world_ * g.T_world_css(omega);
    rays[i] = Ray{T * g.laser_point(), T.linear() * g.beam_direction(g.beam_angle(i, kN)), 0.0,
                  g.max_range_mm};
    ccd[i] = T * g.ccd_point();
    truth.omega_rad[i] = omega;
  }
  std::array<Hit, kN> hits;
  caster_.cast(rays, hits);
  // Return rays from each in-range hit to the CCD point (fig. 4.16): blocked means no return.
  std::array<Ray, kN> back;
  std::array<int, kN> back_index;
  int n_back = 0;
  for (int i = 0; i < kN; ++i) {
    truth.range_mm[i] = kNaN;
    truth.point_scene[i] = truth.normal_scene[i] = Vector3d::Constant(kNaN);
    truth.object[i] = -1;
    if (!hits[i].valid || hits[i].t < g.min_range_mm) continue;
    const Vector3d to_ccd = ccd[i] - hits[i].point;
    const double dist = to_ccd.norm();
    back[n_back] = Ray{hits[i].point, to_ccd / dist, kSurfaceEps, dist - kSurfaceEps};
    back_index[n_back++] = i;
  }
  std::array<std::uint8_t, kN> blocked{};
  caster_.occluded(std::span<const Ray>(back.data(), n_back),
                   std::span<std::uint8_t>(blocked.data(), n_back));
  for (int j = 0; j < n_back; ++j) {
    if (blocked[j]) continue;
    const int i = back_index[j];
    truth.range_mm[i] = hits[i].t;
    truth.point_scene[i] = hits[i].point;
    truth.normal_scene[i] = hits[i].normal;
    truth.object[i] = hits[i].object;
  }
  return truth;
}

}  // namespace rangefit::sim
