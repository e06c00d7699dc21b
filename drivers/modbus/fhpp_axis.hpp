#pragma once
// The linear axis of the stripe-sensor cell (thesis 5.2.1): a Festo drive in FHPP direct mode over
// Modbus TCP (or RTU). A poll thread exchanges one telegram per period (absolute-time schedule),
// stamps each position at the request/reply midpoint with the round trip as its uncertainty, and
// recovers from link faults by itself; motion commands block until the drive acknowledges them.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "drivers/modbus/fhpp_codec.hpp"
#include "drivers/modbus/fhpp_commander.hpp"
#include "drivers/modbus/modbus_link.hpp"
#include "drivers/modbus/position_check.hpp"
#include "hal/bounded_queue.hpp"
#include "hal/source.hpp"

namespace rangefit::drivers {

struct FhppAxisConfig {
  std::string name = "linear_axis";
  ModbusLinkConfig link;
  fhpp::ByteOrder byte_order = fhpp::ByteOrder::kLowByteFirst;
  fhpp::AxisScale scale;
  PositionCheckConfig travel;  // limits for moves and for the plausibility check (mm)
  hal::Duration poll_period = std::chrono::milliseconds(10);      // 10-20 ms in the cell
  hal::Duration max_round_trip = std::chrono::milliseconds(20);   // above: sample invalid
  hal::Duration backoff_initial = std::chrono::milliseconds(20);  // reconnect back-off, doubled
  hal::Duration backoff_max = std::chrono::seconds(1);            // per failure up to this cap
  // The drive's own connection timeout (FHPP fault 47h/48h); the poll period must stay well below.
  hal::Duration drive_comm_timeout = std::chrono::seconds(1);
  bool auto_reset_comm_fault = true;  // acknowledge a connection-timeout fault once polling again
  hal::Duration command_timeout = std::chrono::milliseconds(500);  // wait for the drive's ACK
  std::size_t queue_capacity = 4096;
};

// Driver-specific counters beside hal::StreamCounters.
struct FhppAxisStats {
  std::uint64_t exchanges = 0;            // successful telegram exchanges
  std::uint64_t connect_attempts = 0;     // link opens tried (the back-off spaces them out)
  std::uint64_t late_round_trips = 0;     // samples marked invalid: round trip over the limit
  std::uint64_t implausible = 0;          // samples marked invalid: position implausible
  std::uint64_t bad_replies = 0;          // late/foreign replies caught by transaction id or length
  std::uint64_t exceptions = 0;           // Modbus exception replies
  std::uint64_t takeovers = 0;            // another master took control (SCON FCT/MMI)
  std::uint64_t comm_timeout_faults = 0;  // drive FAULT attributed to its connection timeout
  bool fell_back_to_03_10 = false;
};

class FhppAxis final : public hal::LinearAxis {
 public:
  // clock: nullptr = CLOCK_MONOTONIC. The clock must outlive the driver.
  explicit FhppAxis(FhppAxisConfig config, hal::Clock* clock = nullptr);
  ~FhppAxis() override;

  std::string name() const override { return config_.name; }
  hal::Status start() override;  // validates the configuration, starts the poll thread
  void stop() override;
  hal::DeviceHealth health() const override;
  std::size_t read(std::vector<hal::AxisSample>& out, hal::Duration timeout) override;

  hal::Status enable() override;
  hal::Status home() override;
  hal::Status move_to(double position_mm, double speed_mm_s) override;
  hal::Status halt() override;
  bool motion_complete() const override;
  // Not in the HAL: acknowledge a drive FAULT (RESET edge); then enable() again.
  hal::Status reset_fault();
  hal::Status disable();

  FhppAxisStats stats() const;
  // Every distinct problem reported so far, oldest first (at most kMaxEvents).
  std::vector<std::string> events() const;
  std::optional<hal::AxisSample> latest() const;
  static constexpr std::size_t kMaxEvents = 64;

 private:
  void run();
  void cycle();
  void on_link_error(const LinkResult& r);
  void on_reply(const LinkResult& r, const fhpp::InputTelegram& in);
  void schedule_retry(hal::Timestamp now);
  // Under mutex_: sets state and message; a new message is logged and kept in events_.
  void report(hal::DeviceState state, const std::string& message);
  template <class Request>
  hal::Status command(const char* what, Request request);

  FhppAxisConfig config_;
  std::unique_ptr<hal::Clock> own_clock_;
  hal::Clock* clock_;
  ModbusLink link_;
  hal::BoundedQueue<hal::AxisSample> queue_;

  mutable std::mutex mutex_;
  std::condition_variable cv_;
  fhpp::Commander commander_;
  hal::DeviceHealth health_;
  FhppAxisStats stats_;
  std::deque<std::string> events_;
  std::optional<hal::AxisSample> latest_;
  std::optional<PositionReference> previous_;
  bool connected_ = false;
  bool in_fault_ = false;
  bool comm_fault_ = false;
  bool config_error_ = false;
  bool taken_over_ = false;

  // Poll-thread only.
  bool ever_connected_ = false;
  int failures_ = 0;
  hal::Timestamp retry_at_{};
  std::optional<hal::Timestamp> last_ok_;

  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace rangefit::drivers
