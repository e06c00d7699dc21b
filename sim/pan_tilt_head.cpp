#include "sim/pan_tilt_head.hpp"

#include <algorithm>
#include <cmath>

#include "sim/simulated_stream.hpp"

namespace rangefit::sim {
namespace {

hal::Duration seconds(double s) { return hal::Duration(std::llround(s * 1e9)); }

}  // namespace

class PanTiltHead::AngleDevice final : public SimulatedStream<hal::PanTiltSample> {
 public:
  AngleDevice(const PanTiltHead& head, hal::Clock& clock)
      : SimulatedStream("sim-pan-tilt", clock, head.options_.angle_faults, head.options_.seed, 5),
        head_(head) {}

 protected:
  hal::Timestamp due(std::uint64_t k) const override { return sample_time(k); }

  void make(std::uint64_t k, std::mt19937_64& rng, hal::PanTiltSample& s) override {
    const FaultOptions& f = faults();
    const bool stale = k > 0 && std::bernoulli_distribution(f.stale_probability)(rng);
    const hal::Timestamp t = sample_time(k);
    s.stamp = t;
    if (f.stamp_jitter_sigma.count() > 0) {
      std::normal_distribution<double> j(0.0, static_cast<double>(f.stamp_jitter_sigma.count()));
      s.stamp += hal::Duration(static_cast<std::int64_t>(j(rng)));
    }
    s.pan_rad = head_.pan_at(stale ? sample_time(k - 1) : t);
    s.tilt_rad = head_.options_.tilt_rad;
    s.valid = true;
  }

 private:
  hal::Timestamp sample_time(std::uint64_t k) const {
    return head_.start_ + seconds(static_cast<double>(k) / head_.options_.angle_rate_hz);
  }
  const PanTiltHead& head_;
};

PanTiltHead::PanTiltHead(const Scene& scene, const RayCaster& caster, PanTiltOptions options,
                         hal::Clock& clock)
    : options_(std::move(options)),
      T_scene_world_(scene.mounts.T_scene_pantilt),
      start_(clock.now()) {
  RangerOptions r;
  r.ranger = options_.geometry.ranger;
  r.profile_rate_hz = options_.geometry.profile_rate_hz;
  r.exposure = options_.exposure;
  r.quantise = options_.quantise;
  r.faults = options_.ranger_faults;
  r.seed = options_.seed;
  ranger_ = make_simulated_ranger(
      "sim-pan-tilt-ranger", caster, r, [this](hal::Timestamp t) { return T_scene_ranger(t); },
      clock, start_);
  angles_ = std::make_unique<AngleDevice>(*this, clock);
}

PanTiltHead::~PanTiltHead() = default;

hal::RangerSource& PanTiltHead::ranger() { return *ranger_; }
hal::PanTiltSource& PanTiltHead::angles() { return *angles_; }

hal::Timestamp PanTiltHead::sweep_end() const {
  const auto& g = options_.geometry;
  return start_ + seconds(g.sweep_angle_rad / g.sweep_rate_rad_s);
}

double PanTiltHead::pan_at(hal::Timestamp t) const {
  const auto& g = options_.geometry;
  const double dt = static_cast<double>((t - start_).count()) * 1e-9;
  const double half = 0.5 * g.sweep_angle_rad;
  return g.pan_zero_rad + std::clamp(-half + g.sweep_rate_rad_s * dt, -half, half);
}

Eigen::Isometry3d PanTiltHead::T_scene_ranger(hal::Timestamp t) const {
  return T_scene_world_ * options_.geometry.T_world_ranger(pan_at(t), options_.tilt_rad);
}

}  // namespace rangefit::sim
