#pragma once
// The mobile scanning head's devices on the real transports (thesis 5.2.1, fig. 5.14-5.16): its
// pan and tilt axes as two CiA 402 drives (sim::SimCia402Node) and its laser-stripe ranger
// (sim::SimProfileRanger, CAN FD) on the head's own CAN bus. The cell program pans the head back
// and forth (SweepTimeline: pan_zero -half .. +half at the sweep rate, back, again) with the tilt
// held; every SYNC is answered with the axes' angles at that instant, and every exposure shows
// the profile cast at the pan the head has then (StripeProfiles over the pan), so the service
// records a sweep as the simulated head (sim::PanTiltHead) casts it. One axis can be made to stop
// answering (silent: no TPDOs, no heartbeats), also by the peer itself the moment the pan passes
// the sweep's centre on a forward stroke (a shell under emulation cannot hit a 4 s stroke). A
// second camera of the head's laser plane (its own ranger on the same bus, the profiles cast
// from the plane's other side) shows the same pans; it stays silent until switched on.

#include <atomic>
#include <memory>

#include "hal/pan_tilt_geometry.hpp"
#include "hal/time.hpp"
#include "test/hil/cell_peer/stripe_profiles.hpp"
#include "test/hil/cell_peer/sweep_timeline.hpp"
#include "test/support/can_bus.hpp"
#include "test/support/can_cia402_node.hpp"
#include "test/support/can_profile_ranger.hpp"

namespace rangefit::hil {

struct PanTiltHeadOptions {
  std::uint8_t pan_node = 1;  // the drivers' defaults (daemon/service/bus_addresses.hpp)
  std::uint8_t tilt_node = 2;
  std::uint8_t ranger_node = 0x20;
  std::uint8_t second_ranger_node = 0x21;  // the second camera's, when it has profiles
  double profile_rate_hz = 25.0;
  double pan_zero_rad = 0.0;  // encoder zero, as hal::PanTiltGeometry
  double tilt_rad = 0.0;      // held
  SweepTimeline sweep{.half_rad = 10.0 * 3.14159265358979323846 / 180.0,
                      .forward_s = 4.0,
                      .end_dwell_s = 0.3,
                      .return_s = 1.5,
                      .dwell_s = 0.5};
};

class PanTiltHeadPeer {
 public:
  // profiles (cast over the pan, pan_tilt_sweep; and second, a second camera's, when given)
  // must outlive the peer; the first stroke begins at origin.
  PanTiltHeadPeer(const StripeProfiles& profiles, PanTiltHeadOptions options, hal::Timestamp origin,
                  const StripeProfiles* second = nullptr);

  // The three devices (four with a second camera), to add to the head's CAN bus.
  void add_to(sim::SimCanBus& bus) const;
  // Reported pan (rad, encoder) at host time t.
  double pan_at(hal::Timestamp t) const;
  // The tilt axis stops answering (silent) or answers again; stop_tilt_mid_stroke() makes it
  // stop when the pan next passes pan_zero moving forward.
  void set_tilt_silent(bool silent);
  void stop_tilt_mid_stroke() { stop_armed_ = true; }
  // The head's devices fall silent (no heartbeats, TPDOs or profiles; their state is kept) or
  // answer again, so that its traffic loads the emulated VM only while a test uses the head.
  void set_powered(bool on);
  bool powered() const { return powered_; }
  // The second camera streams only while on (and the head powered): its CAN FD traffic doubles
  // the head's, which moves the other streams' stamps under emulation.
  void set_second_camera_on(bool on);
  bool has_second_camera() const { return second_ranger_ != nullptr; }
  bool second_camera_on() const { return second_on_; }
  bool tilt_silent() const { return tilt_silent_; }
  std::uint64_t profiles_sent() const { return ranger_->profiles_sent(); }
  std::uint64_t syncs_answered() const { return pan_->syncs_answered(); }
  double cycle_s() const { return options_.sweep.cycle_s(); }

 private:
  double exposed_at(hal::Timestamp exposure);  // on the bus thread; fires the armed stop

  PanTiltHeadOptions options_;
  hal::Timestamp origin_;
  std::shared_ptr<sim::SimCia402Node> pan_, tilt_;
  std::shared_ptr<sim::SimProfileRanger> ranger_, second_ranger_;
  std::atomic<bool> stop_armed_{false}, tilt_silent_{false}, powered_{true}, second_on_{false};
  double last_pan_ = 0.0;  // bus thread only
};

}  // namespace rangefit::hil
