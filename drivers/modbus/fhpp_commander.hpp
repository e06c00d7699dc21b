#pragma once
// Host side of the FHPP direct-mode state machine: turns motion requests (enable, home, move,
// halt, reset) into output telegrams with the edge handshakes the drive expects, and refuses
// requests the drive's last status makes pointless (FAULT, another master, not referenced).
// Pure and single-threaded: the driver calls it under its own lock.
//
// Handshake (Festo FHPP): START or HOME is raised only while SPOS.ACK is low, held until the drive
// raises ACK (command accepted), then dropped; the drive drops ACK in turn. RESET is a rising edge
// held until FAULT clears (at most kResetCycles telegrams).

#include <cstdint>
#include <optional>

#include "drivers/modbus/fhpp_codec.hpp"
#include "hal/device.hpp"

namespace rangefit::drivers::fhpp {

class Commander {
 public:
  static constexpr int kResetCycles = 5;

  explicit Commander(AxisScale scale) : scale_(scale) {}

  // The latest input telegram; every request is checked against it.
  void observe(const InputTelegram& in);
  // Forget the drive's status (connection lost): requests are refused until the next observe().
  void forget();
  // The telegram to write in this cycle; advances the edge handshakes.
  OutputTelegram next_output();

  // Each accepted request gets a ticket; accepted(ticket) turns true once the drive has
  // acknowledged it (ACK for start/home, ENABLED+OPEN for enable, HALT low for halt).
  struct Ticket {
    std::uint64_t id = 0;
  };
  // Refusals carry the reason and the drive's SCON/SPOS.
  hal::Status request_enable(Ticket& t);
  void request_disable();
  hal::Status request_home(Ticket& t);
  // Travel limits in mm; speed in mm/s (sent as whole % of AxisScale::max_speed_mm_s).
  hal::Status request_move(double position_mm, double speed_mm_s, double min_mm, double max_mm,
                           Ticket& t);
  hal::Status request_halt(Ticket& t);
  hal::Status request_reset(Ticket& t);

  bool accepted(Ticket t) const { return t.id <= accepted_id_; }
  // The last move or homing has finished (drive reports MC, nothing pending).
  bool motion_complete() const;
  const std::optional<InputTelegram>& last_input() const { return last_; }

 private:
  enum class Edge : std::uint8_t { kIdle, kWaitAckLow, kRaised, kWaitAckDrop };
  hal::Status refuse_if_unusable(const char* what) const;
  std::uint64_t issue(Ticket& t) { return t.id = ++issued_id_; }

  AxisScale scale_;
  std::optional<InputTelegram> last_;
  bool enable_ = false;
  bool halt_ = false;
  std::uint8_t velocity_pct_ = 0;
  std::int32_t target_inc_ = 0;
  std::uint8_t edge_bit_ = 0;  // kCposStart or kCposHome while an edge is in flight
  Edge edge_ = Edge::kIdle;
  int reset_cycles_ = 0;
  std::uint64_t issued_id_ = 0;
  std::uint64_t accepted_id_ = 0;
  std::uint64_t pending_id_ = 0;  // ticket waiting for the drive's acknowledgement
  enum class Pending : std::uint8_t {
    kNone,
    kEnable,
    kEdge,
    kHalt,
    kReset
  } pending_ = Pending::kNone;
};

}  // namespace rangefit::drivers::fhpp
