#pragma once
// The Circular Scanning Sensor over USB as a hal::CssSource. A supervisor thread opens
// the device (retrying with back-off while it is absent), reads GET_INFO, synchronises the clock
// with GET_TIME bursts, sends START and keeps the bulk stream running; the transport's event thread
// feeds the RevolutionTranslator and pushes revolutions into a bounded queue. Unplug cancels the
// stream, marks the scan incomplete (health message, a sequence discontinuity on return) and the
// supervisor reconnects when the device comes back, without a restart of the caller.

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "drivers/usb/revolution_translator.hpp"
#include "drivers/usb/usb_transport.hpp"
#include "hal/bounded_queue.hpp"
#include "hal/source.hpp"

namespace rangefit::drivers::css_usb {

struct CssUsbOptions {
  std::string name = "css";
  std::size_t queue_capacity = 64;    // revolutions (~9 s at 7 Hz)
  int transfers_in_flight = 6;        // 4-8 keeps the endpoint busy without waste
  std::uint16_t rate_centi_hz = 700;  // SET_RATE: revolutions per second x 100
  hal::Duration sync_interval = std::chrono::seconds(1);  // GET_TIME burst period
  int sync_burst = 4;                                     // exchanges per burst (fastest dominates)
  hal::Duration retry_min = std::chrono::milliseconds(100);  // open back-off, doubling
  hal::Duration retry_max = std::chrono::seconds(5);
  ClockOptions clock;
};

class CssUsbDriver final : public hal::CssSource {
 public:
  // Revolutions are stamped in the transport's base, CLOCK_MONOTONIC (bulk completions and the
  // GET_TIME windows of UsbTransport::control_in_timed); the driver takes no stamps of its own.
  CssUsbDriver(std::unique_ptr<UsbTransport> transport, CssUsbOptions options);
  ~CssUsbDriver() override;

  std::string name() const override { return options_.name; }
  // Starts the supervisor; Ok even when the device is absent (it keeps retrying).
  hal::Status start() override;
  void stop() override;
  hal::DeviceHealth health() const override;
  std::size_t read(std::vector<hal::CssRevolution>& out, hal::Duration timeout) override;

  std::optional<DeviceInfo> info() const;
  // Fitted device clock rate relative to the host, ppm (0 until the drift fit is trusted).
  double clock_drift_ppm() const;
  // Revolutions stamped from transfer completion because the clock was not synchronised.
  std::uint64_t host_stamped() const;

 private:
  void supervise();
  bool connect();
  void disconnect(const std::string& why);
  void sync_clock();
  void on_data(std::span<const std::uint8_t> bytes, hal::Timestamp completed);
  void on_event(TransportEvent event);
  void set_state(hal::DeviceState state, std::string message);

  std::unique_ptr<UsbTransport> transport_;
  CssUsbOptions options_;
  hal::BoundedQueue<hal::CssRevolution> queue_;

  mutable std::mutex translator_mutex_;  // event thread (feed) vs supervisor (exchanges)
  RevolutionTranslator translator_;

  mutable std::mutex mutex_;  // state, message, info, wake-up flags
  std::condition_variable wake_;
  hal::DeviceState state_ = hal::DeviceState::kDisconnected;
  std::string message_;
  std::optional<DeviceInfo> info_;
  bool running_ = false;
  bool lost_ = false;     // NO_DEVICE / hotplug left seen
  bool arrived_ = false;  // hotplug arrived seen
  bool stalled_ = false;
  bool incomplete_ = false;  // a scan was cut by an unplug and streaming has not resumed
  std::thread supervisor_;

  std::atomic<std::uint64_t> samples_{0};
  std::atomic<std::uint64_t> stalls_{0};
  std::atomic<std::uint64_t> transfer_errors_{0};
  std::atomic<std::uint64_t> reconnects_{0};
  std::atomic<std::uint64_t> motor_faults_{0};
  bool ever_connected_ = false;
};

}  // namespace rangefit::drivers::css_usb
