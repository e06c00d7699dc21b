#include "drivers/usb/css_usb_driver.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace rangefit::drivers::css_usb {

CssUsbDriver::CssUsbDriver(std::unique_ptr<UsbTransport> transport, CssUsbOptions options)
    : transport_(std::move(transport)),
      options_(std::move(options)),
      queue_(options_.queue_capacity),
      translator_(options_.clock) {
  transport_->set_event_handler([this](TransportEvent e) { on_event(e); });
}

CssUsbDriver::~CssUsbDriver() {
  stop();
  // The transport's threads call back into this object: end them while its members still live.
  transport_.reset();
}

hal::Status CssUsbDriver::start() {
  std::lock_guard lock(mutex_);
  if (running_) return hal::Status::Ok();
  running_ = true;
  supervisor_ = std::thread([this] { supervise(); });
  return hal::Status::Ok();
}

void CssUsbDriver::stop() {
  {
    std::lock_guard lock(mutex_);
    if (!running_) return;
    running_ = false;
  }
  wake_.notify_all();
  if (supervisor_.joinable()) supervisor_.join();
}

void CssUsbDriver::set_state(hal::DeviceState state, std::string message) {
  std::lock_guard lock(mutex_);
  state_ = state;
  // An unplug stays in the message until streaming resumes: the scan it cut is incomplete.
  if (!message.empty()) message_ = (incomplete_ ? "scan incomplete (unplugged); " : "") + message;
}

void CssUsbDriver::supervise() {
  hal::Duration backoff = options_.retry_min;
  std::unique_lock lock(mutex_);
  while (running_) {
    if (state_ != hal::DeviceState::kStreaming) {
      lock.unlock();
      const bool ok = connect();
      lock.lock();
      if (!ok) {
        // Wait for the back-off, or earlier when hotplug reports an arrival.
        wake_.wait_for(lock, backoff, [&] { return !running_ || arrived_; });
        arrived_ = false;
        backoff = std::min(backoff * 2, options_.retry_max);
        continue;
      }
      backoff = options_.retry_min;
    }
    wake_.wait_for(lock, options_.sync_interval, [&] { return !running_ || lost_ || stalled_; });
    if (!running_) break;
    if (lost_) {
      lock.unlock();
      disconnect("device lost mid-stream");
      lock.lock();
      continue;
    }
    if (stalled_) {
      stalled_ = false;
      lock.unlock();
      if (!transport_->recover_stall()) disconnect("stall could not be cleared");
      lock.lock();
      continue;
    }
    lock.unlock();
    sync_clock();
    lock.lock();
  }
  const bool streaming = state_ == hal::DeviceState::kStreaming;
  lock.unlock();
  // Best effort: when the device is already gone the request fails, and close() follows anyway.
  if (streaming) static_cast<void>(transport_->control_out(Request::kStop, 0));
  transport_->close();
  set_state(hal::DeviceState::kDisconnected, "stopped");
}

bool CssUsbDriver::connect() {
  {
    std::lock_guard lock(mutex_);
    lost_ = false;
    stalled_ = false;
    state_ = hal::DeviceState::kConnecting;
  }
  if (const hal::Status s = transport_->open(); !s) {
    set_state(hal::DeviceState::kDisconnected, "open failed: " + s.message);
    return false;
  }
  std::array<std::uint8_t, kInfoBytes> bytes{};
  std::size_t received = 0;
  const hal::Status got = transport_->control_in(Request::kGetInfo, 0, bytes, received);
  const auto info = got ? decode_info(std::span(bytes).first(received)) : std::nullopt;
  if (!info || info->samples_per_revolution != kSamples) {
    transport_->close();
    set_state(hal::DeviceState::kDisconnected, "GET_INFO failed or unsupported device");
    return false;
  }
  {
    std::lock_guard lock(translator_mutex_);
    translator_.reset();  // a (re)connected device has restarted its counters
  }
  // Stream synchronised from the first revolution: under load a whole burst can exceed the
  // round-trip limit, so retry a few bursts before falling back to completion stamps.
  // Two bursts at least: the first exchange after opening is often slow.
  for (int burst = 0; burst < 10; ++burst) {
    sync_clock();
    std::lock_guard lock(translator_mutex_);
    if (burst >= 1 && translator_.clock().synchronised()) break;
  }
  const hal::Status rate = transport_->control_out(Request::kSetRate, options_.rate_centi_hz);
  const hal::Status streaming =
      rate ? transport_->start_streaming(
                 [this](std::span<const std::uint8_t> b, hal::Timestamp t) { on_data(b, t); },
                 options_.transfers_in_flight)
           : rate;
  const hal::Status started = streaming ? transport_->control_out(Request::kStart, 0) : streaming;
  if (!started) {
    transport_->close();
    set_state(hal::DeviceState::kDisconnected, "start failed: " + started.message);
    return false;
  }
  if (ever_connected_) ++reconnects_;
  ever_connected_ = true;
  {
    std::lock_guard lock(mutex_);
    incomplete_ = false;  // streaming resumed: the next health message no longer says incomplete
  }
  set_state(hal::DeviceState::kConnecting, "streaming");
  spdlog::info("{}: streaming from {} (firmware {:#x})", options_.name, info->serial,
               info->firmware);
  std::lock_guard lock(mutex_);
  info_ = info;
  state_ = hal::DeviceState::kStreaming;  // a loss during connect is handled by supervise()
  return true;
}

void CssUsbDriver::disconnect(const std::string& why) {
  spdlog::warn("{}: {}", options_.name, why);
  {
    std::lock_guard lock(mutex_);
    incomplete_ = state_ == hal::DeviceState::kStreaming;
  }
  transport_->close();
  {
    std::lock_guard lock(translator_mutex_);
    translator_.reset();
  }
  set_state(hal::DeviceState::kDisconnected, why);
}

void CssUsbDriver::sync_clock() {
  for (int k = 0; k < options_.sync_burst; ++k) {
    std::array<std::uint8_t, 8> reply{};
    std::size_t received = 0;
    UsbTransport::Window window;
    const hal::Status s =
        transport_->control_in_timed(Request::kGetTime, 0, reply, received, window);
    const hal::Timestamp before = window.submitted;
    const hal::Timestamp after = window.completed;
    if (!s || received != reply.size()) continue;
    std::uint64_t device_us = 0;
    for (int i = 7; i >= 0; --i) device_us = device_us << 8 | reply[static_cast<std::size_t>(i)];
    std::lock_guard lock(translator_mutex_);
    translator_.add_exchange(before, device_us, after);
  }
}

void CssUsbDriver::on_data(std::span<const std::uint8_t> bytes, hal::Timestamp completed) {
  std::lock_guard lock(translator_mutex_);
  translator_.feed(bytes, completed, [&](const hal::CssRevolution& r, const StreamParser::Frame&) {
    if ((r.flags & hal::kCssMotorLocked) == 0 || (r.flags & hal::kCssOverTemperature) != 0) {
      ++motor_faults_;
    }
    samples_ += 1;
    queue_.push(r);  // drops and counts when the consumer is behind
  });
}

void CssUsbDriver::on_event(TransportEvent event) {
  {
    std::lock_guard lock(mutex_);
    switch (event) {
      case TransportEvent::kNoDevice:
      case TransportEvent::kLeft:
        lost_ = true;
        break;
      case TransportEvent::kStall:
        stalled_ = true;
        ++stalls_;
        break;
      case TransportEvent::kError:
        ++transfer_errors_;
        break;
      case TransportEvent::kArrived:
        arrived_ = true;
        break;
    }
  }
  wake_.notify_all();
}

hal::DeviceHealth CssUsbDriver::health() const {
  hal::DeviceHealth h;
  {
    std::lock_guard lock(mutex_);
    h.state = state_;
    h.message = message_;
    if (info_) h.hardware_id = info_->serial;
  }
  {
    std::lock_guard lock(translator_mutex_);
    const ParserCounters& p = translator_.counters();
    h.counters.gaps = p.gaps;
    h.counters.crc_errors = p.crc_errors;
    h.counters.resyncs = p.resyncs;
  }
  h.counters.samples = samples_;
  h.counters.dropped = queue_.dropped();
  h.counters.timeouts = stalls_ + transfer_errors_;
  h.counters.faults = motor_faults_;
  h.counters.reconnects = reconnects_;
  return h;
}

std::size_t CssUsbDriver::read(std::vector<hal::CssRevolution>& out, hal::Duration timeout) {
  return queue_.drain(out, timeout);
}

std::optional<DeviceInfo> CssUsbDriver::info() const {
  std::lock_guard lock(mutex_);
  return info_;
}

double CssUsbDriver::clock_drift_ppm() const {
  std::lock_guard lock(translator_mutex_);
  return translator_.clock().drift_ppm();
}

std::uint64_t CssUsbDriver::host_stamped() const {
  std::lock_guard lock(translator_mutex_);
  return translator_.host_stamped();
}

}  // namespace rangefit::drivers::css_usb
