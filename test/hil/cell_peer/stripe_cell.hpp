#pragma once
// The stripe cell's devices on the real transports (thesis 5.2.1, fig. 5.8): the Festo drive of the
// linear axis (sim::SimFhppDrive, referenced, 0..travel) behind its Modbus TCP server on loopback,
// and the laser-stripe ranger (sim::SimProfileRanger) free-running on the CAN bus. Each exposure
// shows the profile at the drive's exact position at that instant (StripeProfiles), so the table
// moves through the laser plane as the service commands the drive. The server can be stopped and
// started again (same port) to take the axis away mid-scan, also by the peer itself the moment the
// table passes a position (a shell polling the peer under emulation is too slow to hit a sweep).

#include <atomic>
#include <memory>
#include <mutex>

#include "hal/device.hpp"
#include "test/hil/cell_peer/stripe_profiles.hpp"
#include "test/support/can_profile_ranger.hpp"
#include "test/support/modbus_axis_server.hpp"

namespace rangefit::hil {

struct StripeCellPeerOptions {
  int modbus_port = 1502;
  std::uint8_t ranger_node = 0x20;
  std::uint8_t second_ranger_node = 0x21;  // the second camera's, when it has profiles
  double profile_rate_hz = 12.6;  // as the simulated cell (sim::StripeCellOptions)
  double initial_mm = 100.0;      // where the table stands at power-up
};

class StripeCellPeer {
 public:
  // profiles (and second, the profiles of a second camera of the laser plane, when given) must
  // outlive the peer. The second camera's ranger starts silent (set_second_camera_on).
  StripeCellPeer(const StripeProfiles& profiles, StripeCellPeerOptions options,
                 const StripeProfiles* second = nullptr);

  // Starts the server (again) and cancels a stop_axis_past() that has not fired.
  hal::Status start_axis();
  // The server closes its connections and the port refuses new ones; the drive faults after its
  // connection timeout and stops, as a real drive whose master went away.
  void stop_axis();
  // Stops the server once the table passes axis_mm moving up (toward the end of travel), i.e.
  // during a sweep that starts below it.
  void stop_axis_past(double axis_mm) { stop_past_ = axis_mm; }
  bool axis_up() const { return up_; }
  // The ranger, to add to the CAN bus; the second camera's (null without one).
  std::shared_ptr<sim::SimProfileRanger> ranger() const { return ranger_; }
  std::shared_ptr<sim::SimProfileRanger> second_ranger() const { return second_ranger_; }
  // The second camera streams only while on: its CAN FD traffic doubles the bus load, which
  // moves the other streams' stamps under emulation.
  void set_second_camera_on(bool on);
  bool second_camera_on() const { return second_on_; }
  double position_mm() const { return drive_.position_at(hal::monotonic_now()); }
  bool axis_fault() const { return drive_.fault(); }
  std::uint64_t profiles_sent() const { return ranger_->profiles_sent(); }

 private:
  // On the bus thread at every exposure: the drive's position then (and the armed stop).
  double exposed_at(hal::Timestamp exposure);

  sim::SimFhppDrive drive_;
  sim::SimAxisServer server_;
  std::shared_ptr<sim::SimProfileRanger> ranger_;
  std::shared_ptr<sim::SimProfileRanger> second_ranger_;
  std::atomic<bool> second_on_{false};
  std::mutex server_mutex_;  // start and stop come from stdin's commands and the bus thread
  std::atomic<bool> up_{false};
  std::atomic<double> stop_past_{-1.0};  // negative: not armed
  double last_mm_ = 0.0;                 // bus thread only
};

}  // namespace rangefit::hil
