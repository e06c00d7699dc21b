#pragma once
// The seam between the CSS driver and USB: vendor control requests, a stream of bulk IN
// transfers, and hotplug notices. LibusbTransport implements it over libusb-1.0; unit tests use an
// in-process fake that speaks the same wire protocol.

#include <cstdint>
#include <functional>
#include <span>

#include "drivers/usb/css_protocol.hpp"
#include "hal/device.hpp"
#include "hal/time.hpp"

namespace rangefit::drivers::css_usb {

enum class TransportEvent {
  kNoDevice,  // the device went away (unplug, UDC unbound): every transfer has ended
  kStall,     // the bulk endpoint stalled; the driver calls recover_stall()
  kError,     // another transfer error; the transfer was resubmitted
  kArrived,   // hotplug: a matching device appeared (no I/O done yet)
  kLeft,      // hotplug: it left
};

class UsbTransport {
 public:
  // Called from the transport's event thread with each completed bulk transfer and the host
  // CLOCK_MONOTONIC time of its completion. Must not block.
  using DataHandler = std::function<void(std::span<const std::uint8_t>, hal::Timestamp)>;
  // Called from the event thread (or hotplug callback); must not do I/O.
  using EventHandler = std::function<void(TransportEvent)>;

  virtual ~UsbTransport() = default;

  // Sets the event handler before open(); hotplug notices may arrive at any time after.
  virtual void set_event_handler(EventHandler handler) = 0;
  // Finds, opens and claims the device (interface 0); error when absent or busy.
  virtual hal::Status open() = 0;
  // Stops streaming and releases the device. Idempotent.
  virtual void close() = 0;
  // Vendor control IN; returns the bytes received in `received`.
  virtual hal::Status control_in(Request request, std::uint16_t value, std::span<std::uint8_t> data,
                                 std::size_t& received) = 0;
  // Like control_in, with host CLOCK_MONOTONIC stamps that bracket the device's handling of the
  // request as tightly as the transport can (GET_TIME). Default: stamps around control_in.
  struct Window {
    hal::Timestamp submitted{};
    hal::Timestamp completed{};
  };
  virtual hal::Status control_in_timed(Request request, std::uint16_t value,
                                       std::span<std::uint8_t> data, std::size_t& received,
                                       Window& window) {
    window.submitted = hal::monotonic_now();
    const hal::Status s = control_in(request, value, data, received);
    window.completed = hal::monotonic_now();
    return s;
  }
  virtual hal::Status control_out(Request request, std::uint16_t value) = 0;
  // Keeps `in_flight` bulk IN transfers queued, resubmitted on completion.
  virtual hal::Status start_streaming(DataHandler handler, int in_flight) = 0;
  virtual void stop_streaming() = 0;
  // Clears a halted endpoint and restarts the transfers it stopped.
  virtual hal::Status recover_stall() = 0;
};

}  // namespace rangefit::drivers::css_usb
