#include "drivers/usb/libusb_transport.hpp"

#include <libusb.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>

namespace rangefit::drivers::css_usb {
namespace {

hal::Status usb_error(const char* what, int code) {
  return hal::Status::Error(std::string(what) + ": " + libusb_strerror(code));
}

constexpr auto kVendorIn = static_cast<std::uint8_t>(static_cast<int>(LIBUSB_ENDPOINT_IN) |
                                                     static_cast<int>(LIBUSB_REQUEST_TYPE_VENDOR) |
                                                     static_cast<int>(LIBUSB_RECIPIENT_INTERFACE));
constexpr auto kVendorOut = static_cast<std::uint8_t>(static_cast<int>(LIBUSB_ENDPOINT_OUT) |
                                                      static_cast<int>(LIBUSB_REQUEST_TYPE_VENDOR) |
                                                      static_cast<int>(LIBUSB_RECIPIENT_INTERFACE));
// One frame per transfer, rounded up to whole 512-byte high-speed packets so a device that
// pads never overflows the buffer.
constexpr std::size_t kTransferBytes = (kFrameBytes + 511) / 512 * 512;

int hotplug_callback(libusb_context*, libusb_device*, libusb_hotplug_event event, void* self) {
  // No I/O here (libusb forbids it): only tell the driver, which reopens from its own thread.
  auto* transport = static_cast<std::function<void(TransportEvent)>*>(self);
  if (*transport) {
    (*transport)(event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED ? TransportEvent::kArrived
                                                              : TransportEvent::kLeft);
  }
  return 0;
}

}  // namespace

LibusbTransport::LibusbTransport(LibusbOptions options) : options_(options) {
  if (libusb_init(&context_) != 0) {
    context_ = nullptr;
    return;
  }
  events_thread_ = std::thread([this] { event_loop(); });
}

LibusbTransport::~LibusbTransport() {
  close();
  if (hotplug_registered_) libusb_hotplug_deregister_callback(context_, hotplug_handle_);
  running_ = false;
  if (context_) libusb_interrupt_event_handler(context_);
  if (events_thread_.joinable()) events_thread_.join();
  if (context_) libusb_exit(context_);
}

void LibusbTransport::event_loop() {
  while (running_) {
    timeval tv{0, 100000};
    libusb_handle_events_timeout_completed(context_, &tv, nullptr);
  }
}

void LibusbTransport::set_event_handler(EventHandler handler) {
  events_ = std::move(handler);
  if (!context_ || hotplug_registered_ || !libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) return;
  hotplug_registered_ =
      libusb_hotplug_register_callback(
          context_,
          static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED |
                                            LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
          LIBUSB_HOTPLUG_NO_FLAGS, options_.vendor_id, options_.product_id,
          LIBUSB_HOTPLUG_MATCH_ANY, hotplug_callback, &events_, &hotplug_handle_) == 0;
}

hal::Status LibusbTransport::open() {
  if (!context_) return hal::Status::Error("libusb_init failed");
  if (handle_) return hal::Status::Ok();
  handle_ = libusb_open_device_with_vid_pid(context_, options_.vendor_id, options_.product_id);
  if (!handle_) return hal::Status::Error("device not found or not accessible");
  libusb_set_auto_detach_kernel_driver(handle_, 1);
  if (const int rc = libusb_claim_interface(handle_, 0); rc != 0) {
    libusb_close(handle_);
    handle_ = nullptr;
    return usb_error("claim interface 0", rc);
  }
  return hal::Status::Ok();
}

void LibusbTransport::close() {
  stop_streaming();
  if (!handle_) return;
  libusb_release_interface(handle_, 0);
  libusb_close(handle_);
  handle_ = nullptr;
}

hal::Status LibusbTransport::control_in(Request request, std::uint16_t value,
                                        std::span<std::uint8_t> data, std::size_t& received) {
  received = 0;
  if (!handle_) return hal::Status::Error("not open");
  const int rc = libusb_control_transfer(
      handle_, kVendorIn, static_cast<std::uint8_t>(request), value, 0, data.data(),
      static_cast<std::uint16_t>(data.size()), options_.control_timeout_ms);
  if (rc < 0) return usb_error("control IN", rc);
  received = static_cast<std::size_t>(rc);
  return hal::Status::Ok();
}

namespace {

struct ControlWait {  // on the heap: leaked with its transfer if libusb never gives it back
  std::vector<std::uint8_t> buffer;
  std::mutex mutex;
  std::condition_variable done_cv;
  bool done = false;
  hal::Timestamp completed{};
};

void LIBUSB_CALL control_done(libusb_transfer* t) {
  const hal::Timestamp now = hal::monotonic_now();  // first thing: this stamp closes the window
  auto* wait = static_cast<ControlWait*>(t->user_data);
  // Notified under the lock: the waiter frees `wait` as soon as it sees done.
  std::lock_guard lock(wait->mutex);
  wait->completed = now;
  wait->done = true;
  wait->done_cv.notify_all();
}

}  // namespace

hal::Status LibusbTransport::control_in_timed(Request request, std::uint16_t value,
                                              std::span<std::uint8_t> data, std::size_t& received,
                                              Window& window) {
  received = 0;
  if (!handle_) return hal::Status::Error("not open");
  auto wait = std::make_unique<ControlWait>();
  wait->buffer.resize(LIBUSB_CONTROL_SETUP_SIZE + data.size());
  libusb_fill_control_setup(wait->buffer.data(), kVendorIn, static_cast<std::uint8_t>(request),
                            value, 0, static_cast<std::uint16_t>(data.size()));
  libusb_transfer* t = libusb_alloc_transfer(0);
  if (!t) return hal::Status::Error("control IN: out of memory");
  libusb_fill_control_transfer(t, handle_, wait->buffer.data(), control_done, wait.get(),
                               options_.control_timeout_ms);
  window.submitted = hal::monotonic_now();
  if (const int rc = libusb_submit_transfer(t); rc != 0) {
    libusb_free_transfer(t);
    return usb_error("control IN", rc);
  }
  std::unique_lock lock(wait->mutex);
  const auto limit = std::chrono::milliseconds(options_.control_timeout_ms + 500);
  if (!wait->done_cv.wait_for(lock, limit, [&] { return wait->done; })) {
    libusb_cancel_transfer(t);
    if (!wait->done_cv.wait_for(lock, std::chrono::seconds(2), [&] { return wait->done; })) {
      lock.unlock();
      wait.release();  // libusb still owns the transfer and its buffer: leak rather than free
      return hal::Status::Error("control IN: transfer never completed");
    }
  }
  lock.unlock();
  window.completed = wait->completed;
  if (t->status != LIBUSB_TRANSFER_COMPLETED) {
    const int status = t->status;
    libusb_free_transfer(t);
    return hal::Status::Error("control IN: transfer status " + std::to_string(status) +
                              (status == LIBUSB_TRANSFER_STALL ? " (stall)" : ""));
  }
  received = std::min(data.size(), static_cast<std::size_t>(t->actual_length));
  std::copy_n(libusb_control_transfer_get_data(t), received, data.begin());
  libusb_free_transfer(t);
  return hal::Status::Ok();
}

hal::Status LibusbTransport::control_out(Request request, std::uint16_t value) {
  if (!handle_) return hal::Status::Error("not open");
  const int rc = libusb_control_transfer(handle_, kVendorOut, static_cast<std::uint8_t>(request),
                                         value, 0, nullptr, 0, options_.control_timeout_ms);
  return rc < 0 ? usb_error("control OUT", rc) : hal::Status::Ok();
}

hal::Status LibusbTransport::start_streaming(DataHandler handler, int in_flight) {
  if (!handle_) return hal::Status::Error("not open");
  std::lock_guard lock(mutex_);
  if (streaming_) return hal::Status::Ok();
  data_ = std::move(handler);
  streaming_ = true;
  for (int i = 0; i < in_flight; ++i) {
    buffers_.emplace_back(kTransferBytes);
    libusb_transfer* t = libusb_alloc_transfer(0);
    libusb_fill_bulk_transfer(t, handle_, options_.endpoint, buffers_.back().data(),
                              static_cast<int>(kTransferBytes), &LibusbTransport::transfer_done,
                              this, options_.bulk_timeout_ms);
    transfers_.push_back(t);
    if (const int rc = libusb_submit_transfer(t); rc != 0) {
      streaming_ = false;
      return usb_error("submit bulk transfer", rc);
    }
    ++active_;
  }
  return hal::Status::Ok();
}

void LibusbTransport::stop_streaming() {
  std::unique_lock lock(mutex_);
  streaming_ = false;
  for (libusb_transfer* t : transfers_) libusb_cancel_transfer(t);  // finished ones: harmless
  // The callbacks run on the event thread; wait until every transfer has come back.
  idle_.wait_for(lock, std::chrono::seconds(2), [&] { return active_ == 0; });
  if (active_ == 0) {
    for (libusb_transfer* t : transfers_) libusb_free_transfer(t);
  }  // else leak rather than free a transfer libusb still owns
  transfers_.clear();
  buffers_.clear();
  stalled_.clear();
  active_ = 0;
}

hal::Status LibusbTransport::recover_stall() {
  if (!handle_) return hal::Status::Error("not open");
  if (const int rc = libusb_clear_halt(handle_, options_.endpoint); rc != 0) {
    return usb_error("clear halt", rc);
  }
  std::lock_guard lock(mutex_);
  for (libusb_transfer* t : stalled_) {
    if (streaming_ && libusb_submit_transfer(t) == 0) ++active_;
  }
  stalled_.clear();
  return hal::Status::Ok();
}

void LibusbTransport::transfer_done(libusb_transfer* transfer) {
  static_cast<LibusbTransport*>(transfer->user_data)->on_transfer(transfer);
}

void LibusbTransport::on_transfer(libusb_transfer* t) {
  const hal::Timestamp completed = hal::monotonic_now();
  std::optional<TransportEvent> event;
  {
    std::lock_guard lock(mutex_);
    --active_;
    bool resubmit = streaming_;
    switch (t->status) {
      case LIBUSB_TRANSFER_COMPLETED:
      case LIBUSB_TRANSFER_TIMED_OUT:  // partial data is still data; the parser copes
        if (t->actual_length > 0 && data_) {
          data_({t->buffer, static_cast<std::size_t>(t->actual_length)}, completed);
        }
        break;
      case LIBUSB_TRANSFER_STALL:
        stalled_.push_back(t);
        resubmit = false;
        event = TransportEvent::kStall;
        break;
      case LIBUSB_TRANSFER_NO_DEVICE:
        resubmit = false;
        streaming_ = false;
        event = TransportEvent::kNoDevice;
        break;
      case LIBUSB_TRANSFER_CANCELLED:
        resubmit = false;
        break;
      default:
        event = TransportEvent::kError;
        break;
    }
    if (resubmit && libusb_submit_transfer(t) == 0) ++active_;
  }
  idle_.notify_all();
  if (event && events_) events_(*event);
}

}  // namespace rangefit::drivers::css_usb
