#include "test/hil/cell_peer/pan_tilt_head.hpp"

namespace rangefit::hil {

PanTiltHeadPeer::PanTiltHeadPeer(const StripeProfiles& profiles, PanTiltHeadOptions options,
                                 hal::Timestamp origin, const StripeProfiles* second)
    : options_(options), origin_(origin) {
  sim::SimCia402Config pan;
  pan.node = options_.pan_node;
  pan_ = std::make_shared<sim::SimCia402Node>(pan, [this](hal::Timestamp t) { return pan_at(t); });
  sim::SimCia402Config tilt;
  tilt.node = options_.tilt_node;
  tilt_ = std::make_shared<sim::SimCia402Node>(tilt);
  tilt_->set_angle(options_.tilt_rad);
  ranger_ = std::make_shared<sim::SimProfileRanger>(
      ranger_config(profiles, options_.ranger_node, options_.profile_rate_hz),
      [this, &profiles](std::uint32_t, hal::Timestamp exposure, std::span<std::uint16_t> out) {
        profiles.fill(exposed_at(exposure), out);
      });
  if (second == nullptr) return;
  // The same laser plane at the same pan, seen from its other side: only the pan at the exposure
  // (the armed tilt stop is the first camera's).
  second_ranger_ = std::make_shared<sim::SimProfileRanger>(
      ranger_config(*second, options_.second_ranger_node, options_.profile_rate_hz),
      [this, second](std::uint32_t, hal::Timestamp exposure, std::span<std::uint16_t> out) {
        second->fill(pan_at(exposure), out);
      });
  second_ranger_->set_silent(true);
}

void PanTiltHeadPeer::add_to(sim::SimCanBus& bus) const {
  bus.add(pan_);
  bus.add(tilt_);
  bus.add(ranger_);
  if (second_ranger_) bus.add(second_ranger_);
}

double PanTiltHeadPeer::pan_at(hal::Timestamp t) const {
  const double since = static_cast<double>((t - origin_).count()) * 1e-9;
  return options_.pan_zero_rad + options_.sweep.angle_at(since, options_.sweep.cycle_s());
}

void PanTiltHeadPeer::set_tilt_silent(bool silent) {
  if (!silent) stop_armed_ = false;
  tilt_->set_silent(silent);
  tilt_silent_ = silent;
}

void PanTiltHeadPeer::set_powered(bool on) {
  if (on == powered_) return;
  stop_armed_ = false;
  pan_->set_silent(!on);
  tilt_->set_silent(!on || tilt_silent_);
  ranger_->set_silent(!on);
  if (second_ranger_) second_ranger_->set_silent(!on || !second_on_);
  powered_ = on;
}

void PanTiltHeadPeer::set_second_camera_on(bool on) {
  if (!second_ranger_) return;
  second_on_ = on;
  second_ranger_->set_silent(!on || !powered_);
}

double PanTiltHeadPeer::exposed_at(hal::Timestamp exposure) {
  const double pan = pan_at(exposure);
  if (stop_armed_ && last_pan_ < options_.pan_zero_rad && pan >= options_.pan_zero_rad) {
    stop_armed_ = false;
    set_tilt_silent(true);
  }
  last_pan_ = pan;
  return pan;
}

}  // namespace rangefit::hil
