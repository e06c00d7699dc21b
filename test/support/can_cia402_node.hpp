#pragma once
// A simulated CiA 402 drive: boots (heartbeat 00), goes operational on NMT start, answers every
// SYNC with TPDO1 (statusword + position actual value of the simulated angle at the SYNC's
// receive instant) and optionally TPDO2, produces heartbeats at the 0x1017 period (settable by
// expedited SDO), answers its serial number (identity object 0x1018:04) by expedited SDO upload.
// Faults for tests: silence, reboot, dropped/duplicated/short TPDOs, EMCY, a serial request that
// is aborted (object absent) or never answered.

#include <atomic>
#include <functional>

#include "drivers/can/cia402_codec.hpp"
#include "test/support/can_bus.hpp"

namespace rangefit::sim {

// How the node answers an SDO upload of 0x1018:04.
enum class SimIdentityReply : std::uint8_t { kSerial, kAbort, kSilent };

struct SimCia402Config {
  std::uint8_t node = 1;
  double rad_per_increment = 1e-6;
  double offset_rad = 0.0;
  bool tpdo2 = false;
  std::uint16_t heartbeat_ms = 100;
  std::uint16_t statusword = 0x0637;  // operation enabled, voltage enabled, remote
  std::uint32_t serial = 0;           // 0x1018:04; 0 = 402000 + node
  SimIdentityReply identity = SimIdentityReply::kSerial;
};

class SimCia402Node final : public SimCanDevice {
 public:
  // angle(t) in rad at CLOCK_MONOTONIC t; the default is the value of set_angle().
  explicit SimCia402Node(SimCia402Config config,
                         std::function<double(hal::Timestamp)> angle = nullptr);

  void on_frame(const drivers::can::CanFrame& frame, drivers::can::CanTransport& bus) override;
  hal::Timestamp tick(hal::Timestamp now, drivers::can::CanTransport& bus) override;

  void set_angle(double rad) { angle_value_ = rad; }
  // Fault injection (thread-safe; applied on the bus thread).
  void set_silent(bool silent) { silent_ = silent; }
  void reboot() { reboot_ = true; }
  void drop_next_tpdos(int n) { drop_tpdos_ = n; }
  void duplicate_next_tpdo() { duplicate_tpdo_ = true; }
  void short_next_tpdo() { short_tpdo_ = true; }
  void set_fault(bool fault) { fault_ = fault; }
  void send_emcy_next(std::uint16_t code) { emcy_code_ = code; }
  // Another drive of the same kind put in its place (takes effect with reboot()).
  void set_serial(std::uint32_t serial) { serial_ = serial; }

  std::uint8_t nmt_state() const { return state_; }
  std::uint64_t syncs_answered() const { return answered_; }
  std::uint16_t heartbeat_ms() const { return heartbeat_ms_; }
  std::uint32_t serial() const { return serial_; }
  std::uint64_t identity_requests() const { return identity_requests_; }

 private:
  void answer_sync(hal::Timestamp stamp, drivers::can::CanTransport& bus);
  void answer_sdo(const drivers::can::cia402::Message& m, drivers::can::CanTransport& bus);
  void boot(drivers::can::CanTransport& bus);

  SimCia402Config config_;
  std::function<double(hal::Timestamp)> angle_;
  std::atomic<double> angle_value_{0.0};
  std::atomic<std::uint8_t> state_{drivers::can::cia402::kBootUp};
  std::atomic<std::uint16_t> heartbeat_ms_;
  std::atomic<bool> silent_{false}, reboot_{true}, duplicate_tpdo_{false}, short_tpdo_{false};
  std::atomic<bool> fault_{false}, reschedule_heartbeat_{false};
  std::atomic<int> drop_tpdos_{0};
  std::atomic<std::uint16_t> emcy_code_{0};
  std::atomic<std::uint64_t> answered_{0};
  std::atomic<std::uint32_t> serial_;
  std::atomic<std::uint64_t> identity_requests_{0};
  hal::Timestamp next_heartbeat_{};
};

}  // namespace rangefit::sim
