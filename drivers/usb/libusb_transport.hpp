#pragma once
// UsbTransport over libusb-1.0: asynchronous bulk IN transfers resubmitted from their callback,
// one event thread per transport, vendor control requests, and hotplug callbacks where the
// platform has them (the driver's open back-off polls otherwise). Kernel drivers bound to the
// interface are detached automatically.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "drivers/usb/usb_transport.hpp"

struct libusb_context;
struct libusb_device_handle;
struct libusb_transfer;

namespace rangefit::drivers::css_usb {

struct LibusbOptions {
  std::uint16_t vendor_id = 0x1d6b;  // configurable VID:PID (PROTOCOLS.md)
  std::uint16_t product_id = 0x0105;
  std::uint8_t endpoint = 0x81;       // bulk IN
  unsigned control_timeout_ms = 500;  // a loaded host (HIL VM) needed more than 200 ms
  unsigned bulk_timeout_ms = 1000;    // > one revolution (143 ms at 7 Hz)
};

class LibusbTransport final : public UsbTransport {
 public:
  explicit LibusbTransport(LibusbOptions options = {});
  ~LibusbTransport() override;

  void set_event_handler(EventHandler handler) override;
  hal::Status open() override;
  void close() override;
  hal::Status control_in(Request request, std::uint16_t value, std::span<std::uint8_t> data,
                         std::size_t& received) override;
  // Asynchronous, stamped at submission and in the completion callback on the event thread: the
  // synchronous call adds two thread wake-ups to the reply path only (~50 us under emulation),
  // which biases the exchange midpoint.
  hal::Status control_in_timed(Request request, std::uint16_t value, std::span<std::uint8_t> data,
                               std::size_t& received, Window& window) override;
  hal::Status control_out(Request request, std::uint16_t value) override;
  hal::Status start_streaming(DataHandler handler, int in_flight) override;
  void stop_streaming() override;
  hal::Status recover_stall() override;

 private:
  static void transfer_done(libusb_transfer* transfer);
  void on_transfer(libusb_transfer* transfer);
  void event_loop();

  LibusbOptions options_;
  libusb_context* context_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  int hotplug_handle_ = 0;
  bool hotplug_registered_ = false;
  EventHandler events_;
  DataHandler data_;
  std::vector<libusb_transfer*> transfers_;
  std::vector<std::vector<std::uint8_t>> buffers_;
  std::mutex mutex_;
  std::condition_variable idle_;
  int active_ = 0;  // transfers submitted and not yet finished
  bool streaming_ = false;
  std::vector<libusb_transfer*> stalled_;
  std::atomic<bool> running_{true};
  std::thread events_thread_;
};

}  // namespace rangefit::drivers::css_usb
