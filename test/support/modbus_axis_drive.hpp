#pragma once
// A simulated Festo drive in FHPP direct mode: the state machine behind the 8-byte telegrams
// (enable, stop, halt, start/home handshakes with ACK, fault and RESET edge, connection timeout,
// control owned by one master at a time) and a linear axis moving at constant speed.
// Thread-safe; the Modbus server (modbus_axis_server) feeds it, tests ask it for the truth.

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "drivers/modbus/fhpp_codec.hpp"
#include "hal/time.hpp"

namespace rangefit::sim {

struct SimAxisConfig {
  drivers::fhpp::AxisScale scale;  // increments per mm, speed at 100 %
  double min_mm = 0.0;             // travel, mm; moves are clamped to it
  double max_mm = 1000.0;
  double initial_mm = 100.0;  // position at power-up
  double home_mm = 0.0;       // homing drives here and sets REF
  double homing_speed_mm_s = 200.0;
  bool referenced = false;  // REF at power-up
  // No output telegram from the controlling master for this long: FAULT. Zero = never.
  hal::Duration comm_timeout = std::chrono::seconds(1);
};

class SimFhppDrive {
 public:
  explicit SimFhppDrive(SimAxisConfig config);

  // An output telegram from master `client` at time t. Ignored unless the client holds control:
  // control goes to the first writer, and to a client raising ENABLE while another holds it.
  void write(const drivers::fhpp::OutputTelegram& out, hal::Timestamp t, int client);
  // The input telegram as seen by `client` (FCT/MMI set when another master holds control).
  drivers::fhpp::InputTelegram read(hal::Timestamp t, int client);
  void disconnected(int client);
  // Advances time without a request: the connection timeout and homing completion.
  void tick(hal::Timestamp t);

  // Ground truth for tests: the commanded trajectory, exact at any past or present time.
  double position_at(hal::Timestamp t) const;
  // Latches a drive FAULT (e.g. following error) at time t; RESET clears it.
  void inject_fault(hal::Timestamp t, const std::string& reason);
  bool fault() const;
  std::string fault_reason() const;
  int controller() const;

 private:
  struct Segment {
    hal::Timestamp t0{};
    double p0 = 0.0;
    double v = 0.0;  // mm/s, signed
    hal::Timestamp t1{};
    double p1 = 0.0;
  };
  void update(hal::Timestamp t);
  void move(hal::Timestamp t, double target_mm, double speed_mm_s);
  void stop_motion(hal::Timestamp t);
  void latch_fault(hal::Timestamp t, const std::string& reason);
  double position_locked(hal::Timestamp t) const;
  bool moving(hal::Timestamp t) const;

  SimAxisConfig config_;
  mutable std::mutex mutex_;
  std::vector<Segment> path_;
  std::map<int, drivers::fhpp::OutputTelegram> previous_;  // per client, for edges
  int controller_ = -1;
  bool armed_ = false;
  hal::Timestamp last_request_{};
  bool fault_ = false;
  std::string fault_reason_;
  bool enabled_ = false;
  bool open_ = false;
  bool halt_ = false;
  bool ack_ = false;
  bool warn_ = false;
  bool homing_ = false;
  bool referenced_ = false;
  std::uint8_t velocity_pct_ = 0;
};

}  // namespace rangefit::sim
