#include "sim/stripe_cell.hpp"

#include <atomic>
#include <cmath>

#include "sim/simulated_stream.hpp"

namespace rangefit::sim {
namespace {

double to_s(hal::Duration d) { return static_cast<double>(d.count()) * 1e-9; }

}  // namespace

double AxisMotion::position_locked(hal::Timestamp t) const {
  const double dt = std::max(to_s(t - t0_), 0.0);
  const double dist = std::abs(target_ - p0_);
  const double moved = std::min(speed_ * dt, dist);
  return p0_ + (target_ >= p0_ ? moved : -moved);
}

double AxisMotion::position(hal::Timestamp t) const {
  std::lock_guard lock(mutex_);
  return position_locked(t);
}

double AxisMotion::velocity(hal::Timestamp t) const {
  std::lock_guard lock(mutex_);
  if (t < t0_ || position_locked(t) == target_) return 0.0;
  return target_ >= p0_ ? speed_ : -speed_;
}

hal::Status AxisMotion::move(hal::Timestamp now, double target_mm, double speed_mm_s) {
  if (!std::isfinite(target_mm) || target_mm < 0.0 || target_mm > travel_) {
    return hal::Status::Error("target outside the axis travel [0, " + std::to_string(travel_) +
                              "] mm");
  }
  if (!std::isfinite(speed_mm_s) || speed_mm_s <= 0.0) {
    return hal::Status::Error("speed must be positive");
  }
  std::lock_guard lock(mutex_);
  p0_ = position_locked(now);
  t0_ = now;
  target_ = target_mm;
  speed_ = std::min(speed_mm_s, max_speed_);  // the drive limits the speed
  return hal::Status::Ok();
}

void AxisMotion::halt(hal::Timestamp now) {
  std::lock_guard lock(mutex_);
  p0_ = target_ = position_locked(now);
  t0_ = now;
}

bool AxisMotion::done(hal::Timestamp now) const {
  std::lock_guard lock(mutex_);
  return position_locked(now) == target_;
}

// The FESTO axis as the driver presents it: commands plus polled position samples.
// Polled: a position reply arrives half a round trip after the drive sampled it.
class StripeCell::AxisDevice final : public PolledStream<hal::AxisSample, hal::LinearAxis> {
 public:
  AxisDevice(StripeCell& cell, hal::Clock& clock, hal::Timestamp start)
      : PolledStream("sim-linear-axis", clock, cell.options_.axis_faults, cell.options_.seed, 4,
                     start, cell.options_.axis_poll_hz, cell.options_.axis_round_trip / 2),
        cell_(cell) {}

  hal::Status enable() override {
    enabled_ = true;
    return hal::Status::Ok();
  }
  hal::Status home() override {
    if (!enabled_) return hal::Status::Error("axis not enabled");
    return cell_.motion_.move(clock().now(), 0.0, cell_.options_.geometry.max_speed_mm_s);
  }
  hal::Status move_to(double position_mm, double speed_mm_s) override {
    if (!enabled_) return hal::Status::Error("axis not enabled");
    return cell_.motion_.move(clock().now(), position_mm, speed_mm_s);
  }
  hal::Status halt() override {
    cell_.motion_.halt(clock().now());
    return hal::Status::Ok();
  }
  bool motion_complete() const override { return cell_.motion_.done(clock().now()); }

 protected:
  void fill(hal::Timestamp t, hal::Timestamp read_at, hal::AxisSample& s) override {
    const double res = cell_.options_.axis_resolution_mm;
    const double p = cell_.motion_.position(read_at);
    s.uncertainty = cell_.options_.axis_round_trip;
    s.position_mm = std::round(p / res) * res;
    s.velocity_mm_s = cell_.motion_.velocity(t);
    s.scon = 0x07;  // FHPP: enabled, operation enabled, ready
    s.spos = cell_.motion_.done(t) ? 0x04 : 0x10;
    s.valid = true;
  }

 private:
  StripeCell& cell_;
  std::atomic<bool> enabled_{false};
};

StripeCell::StripeCell(const Scene& scene, const RayCaster& caster, StripeCellOptions options,
                       hal::Clock& clock)
    : options_(std::move(options)),
      T_scene_world_(scene.mounts.T_scene_stripe),
      motion_(options_.geometry.max_speed_mm_s, options_.geometry.axis_travel_mm) {
  const hal::Timestamp start = clock.now();
  const auto add_ranger = [&](const hal::StripeCellGeometry& g, const FaultOptions& faults,
                              std::uint64_t seed) {
    rangers_.push_back(make_simulated_ranger(
        "sim-stripe-ranger", caster,
        {.ranger = g.ranger,
         .profile_rate_hz = options_.profile_rate_hz,
         .quantise = options_.quantise,
         .faults = faults,
         .seed = seed},
        [this, &g](hal::Timestamp t) { return T_scene_ranger(g, t); }, clock, start));
  };
  add_ranger(options_.geometry, options_.ranger_faults, options_.seed);
  for (const StripeCellCamera& c : options_.cameras) add_ranger(c.geometry, c.faults, c.seed);
  axis_ = std::make_unique<AxisDevice>(*this, clock, start);
}

StripeCell::~StripeCell() = default;

hal::RangerSource& StripeCell::ranger() { return *rangers_.front(); }
hal::RangerSource& StripeCell::ranger(std::size_t k) { return *rangers_.at(k); }
hal::LinearAxis& StripeCell::axis() { return *axis_; }

Eigen::Isometry3d StripeCell::T_scene_ranger(hal::Timestamp t) const {
  return T_scene_ranger(options_.geometry, t);
}

Eigen::Isometry3d StripeCell::T_scene_ranger(const hal::StripeCellGeometry& camera,
                                             hal::Timestamp t) const {
  return T_scene_world_ * camera.T_world_ranger(motion_.position(t));
}

}  // namespace rangefit::sim
