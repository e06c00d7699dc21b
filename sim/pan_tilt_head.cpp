#include "sim/pan_tilt_head.hpp"

#include <algorithm>
#include <cmath>

#include "sim/simulated_stream.hpp"

namespace rangefit::sim {

class PanTiltHead::AngleDevice final : public PolledStream<hal::PanTiltSample> {
 public:
  AngleDevice(const PanTiltHead& head, hal::Clock& clock)
      : PolledStream("sim-pan-tilt", clock, head.options_.angle_faults, head.options_.seed, 5,
                     head.start_, head.options_.angle_rate_hz),
        head_(head) {}

 protected:
  void fill(hal::Timestamp, hal::Timestamp read_at, hal::PanTiltSample& s) override {
    s.pan_rad = head_.pan_at(read_at);
    s.tilt_rad = head_.options_.tilt_rad;
    s.valid = true;
  }

 private:
  const PanTiltHead& head_;
};

PanTiltHead::PanTiltHead(const Scene& scene, const RayCaster& caster, PanTiltOptions options,
                         hal::Clock& clock)
    : options_(std::move(options)),
      T_scene_world_(scene.mounts.T_scene_pantilt),
      start_(clock.now()) {
  const auto add_ranger = [&](const hal::StripeRanger& ranger, const FaultOptions& faults,
                              std::uint64_t seed) {
    rangers_.push_back(make_simulated_ranger(
        "sim-pan-tilt-ranger", caster,
        {.ranger = ranger,
         .profile_rate_hz = options_.geometry.profile_rate_hz,
         .exposure = options_.exposure,
         .quantise = options_.quantise,
         .faults = faults,
         .seed = seed},
        [this](hal::Timestamp t) { return T_scene_ranger(t); }, clock, start_));
  };
  add_ranger(options_.geometry.ranger, options_.ranger_faults, options_.seed);
  for (const PanTiltCamera& c : options_.cameras) add_ranger(c.ranger, c.faults, c.seed);
  angles_ = std::make_unique<AngleDevice>(*this, clock);
}

PanTiltHead::~PanTiltHead() = default;

hal::RangerSource& PanTiltHead::ranger() { return *rangers_.front(); }
hal::RangerSource& PanTiltHead::ranger(std::size_t k) { return *rangers_.at(k); }
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
