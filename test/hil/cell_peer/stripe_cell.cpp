#include "test/hil/cell_peer/stripe_cell.hpp"

namespace rangefit::hil {
namespace {

sim::SimAxisConfig drive_config(const StripeCellPeerOptions& o) {
  sim::SimAxisConfig c;
  c.max_mm = hal::StripeCellGeometry{}.axis_travel_mm;
  c.initial_mm = o.initial_mm;
  c.referenced = true;  // homed when the cell was commissioned; the service never homes it
  return c;
}

}  // namespace

StripeCellPeer::StripeCellPeer(const StripeProfiles& profiles, StripeCellPeerOptions options,
                               const StripeProfiles* second)
    : drive_(drive_config(options)),
      server_(drive_, {.host = "127.0.0.1", .port = options.modbus_port}) {
  ranger_ = std::make_shared<sim::SimProfileRanger>(
      ranger_config(profiles, options.ranger_node, options.profile_rate_hz),
      [this, &profiles](std::uint32_t, hal::Timestamp exposure, std::span<std::uint16_t> out) {
        profiles.fill(exposed_at(exposure), out);
      });
  if (second == nullptr) return;
  // The same table under the same laser, seen from the other side: only the drive's position.
  second_ranger_ = std::make_shared<sim::SimProfileRanger>(
      ranger_config(*second, options.second_ranger_node, options.profile_rate_hz),
      [this, second](std::uint32_t, hal::Timestamp exposure, std::span<std::uint16_t> out) {
        second->fill(drive_.position_at(exposure), out);
      });
  second_ranger_->set_silent(true);
}

void StripeCellPeer::set_second_camera_on(bool on) {
  if (!second_ranger_) return;
  second_ranger_->set_silent(!on);
  second_on_ = on;
}

hal::Status StripeCellPeer::start_axis() {
  std::lock_guard lock(server_mutex_);
  stop_past_ = -1.0;
  const hal::Status s = server_.start();
  up_ = static_cast<bool>(s);
  return s;
}

void StripeCellPeer::stop_axis() {
  std::lock_guard lock(server_mutex_);
  server_.stop();
  up_ = false;
}

double StripeCellPeer::exposed_at(hal::Timestamp exposure) {
  // The drive's timers run while its server is down too (the connection-timeout fault).
  drive_.tick(hal::monotonic_now());
  const double mm = drive_.position_at(exposure);
  const double past = stop_past_;
  if (past >= 0.0 && last_mm_ < past && mm >= past) {
    stop_past_ = -1.0;
    stop_axis();
  }
  last_mm_ = mm;
  return mm;
}

}  // namespace rangefit::hil
