#pragma once
// In-process CSS device behind the UsbTransport seam: answers GET_INFO/GET_TIME/START/STOP from a
// device clock with an offset and drift, and streams real protocol frames from its own thread
// (faster than real time). Faults are injected on request: unplug/replug, stall, corrupt CRC,
// skipped sequence numbers, frames split over short transfers.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>
#include <vector>

#include "drivers/usb/css_protocol.hpp"
#include "drivers/usb/usb_transport.hpp"

namespace rangefit::drivers::css_usb::test {

class FakeCssDevice final : public UsbTransport {
 public:
  // The device's us counter reads `count_at_start_us` when the fake is made and runs
  // `drift_ppm` fast from there: its offset to the host clock is whatever the host's uptime
  // makes it, and the counter never runs below zero however recently the host booted.
  FakeCssDevice(double count_at_start_us, double drift_ppm, hal::Duration period)
      : count_at_start_us_(count_at_start_us),
        rate_(1.0 + drift_ppm * 1e-6),
        period_(period),
        started_(hal::monotonic_now()) {}
  ~FakeCssDevice() override { close(); }

  // Device counter at a host time, and the range pattern of sample i of revolution `seq`.
  std::uint64_t counter_at(hal::Timestamp host) const {
    const double us =
        count_at_start_us_ + static_cast<double>((host - started_).count()) / 1e3 * rate_;
    return static_cast<std::uint64_t>(std::floor(std::max(us, 0.0)));
  }
  static std::uint16_t pattern(std::uint32_t seq, std::size_t i) {
    return static_cast<std::uint16_t>((seq * 7 + i * 13) % 60000);
  }
  // Host time of revolution seq's index pulse, as the device saw it (ground truth).
  hal::Timestamp truth(std::uint32_t seq) {
    std::lock_guard lock(mutex_);
    return seq < index_times_.size() ? index_times_[seq] : hal::Timestamp{};
  }

  void set_present(bool present) {
    present_ = present;
    if (!present) {
      halt_stream();
      if (events_) events_(TransportEvent::kNoDevice);
    } else if (events_) {
      events_(TransportEvent::kArrived);
    }
  }
  void corrupt_next() { corrupt_ = true; }
  void skip_next() { skip_ = true; }
  void stall_next() { stall_ = true; }
  void split_transfers(bool split) { split_ = split; }
  int opens() const { return opens_; }

  void set_event_handler(EventHandler handler) override { events_ = std::move(handler); }
  hal::Status open() override {
    if (!present_) return hal::Status::Error("device not found");
    ++opens_;
    open_ = true;
    return hal::Status::Ok();
  }
  void close() override {
    halt_stream();
    open_ = false;
  }
  hal::Status control_in(Request request, std::uint16_t, std::span<std::uint8_t> data,
                         std::size_t& received) override {
    received = 0;
    if (!present_ || !open_) return hal::Status::Error("no device");
    if (request == Request::kGetInfo) {
      DeviceInfo info;
      info.serial = "FAKE-1";
      const auto bytes = encode_info(info);
      received = std::min(bytes.size(), data.size());
      std::copy_n(bytes.begin(), received, data.begin());
    } else if (request == Request::kGetTime && data.size() >= 8) {
      const std::uint64_t now = counter_at(hal::monotonic_now());
      for (std::size_t i = 0; i < 8; ++i) data[i] = static_cast<std::uint8_t>(now >> (8 * i));
      received = 8;
    } else {
      return hal::Status::Error("unsupported request");
    }
    return hal::Status::Ok();
  }
  hal::Status control_out(Request, std::uint16_t) override {
    return present_ && open_ ? hal::Status::Ok() : hal::Status::Error("no device");
  }
  hal::Status start_streaming(DataHandler handler, int) override {
    if (!present_ || !open_) return hal::Status::Error("no device");
    halt_stream();
    std::lock_guard lock(thread_mutex_);
    handler_ = std::move(handler);
    streaming_ = true;
    thread_ = std::thread([this] { stream(); });
    return hal::Status::Ok();
  }
  void stop_streaming() override { halt_stream(); }
  hal::Status recover_stall() override {
    stalled_ = false;
    return hal::Status::Ok();
  }

 private:
  // The test thread (unplug) and the driver's supervisor both stop the stream.
  void halt_stream() {
    std::lock_guard lock(thread_mutex_);
    streaming_ = false;
    if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
  }

  void stream() {
    hal::Timestamp next = hal::monotonic_now();
    while (streaming_) {
      const hal::Timestamp index_pulse = next;
      next += period_;
      std::this_thread::sleep_until(std::chrono::steady_clock::time_point(next));
      if (stalled_) continue;
      if (stall_.exchange(false)) {
        stalled_ = true;
        if (events_) events_(TransportEvent::kStall);
        continue;
      }
      WireRevolution r;
      {
        std::lock_guard lock(mutex_);
        if (skip_.exchange(false)) {
          index_times_.push_back({});
          ++sequence_;
        }
        r.sequence = sequence_++;
        index_times_.push_back(index_pulse);
      }
      r.device_time_us = counter_at(index_pulse);
      r.period_us = static_cast<std::uint32_t>(
          std::llround(static_cast<double>(period_.count()) / 1e3 * rate_));
      r.flags = hal::kCssMotorLocked | hal::kCssLaserOn;
      for (std::size_t i = 0; i < kSamples; ++i) r.samples[i] = {pattern(r.sequence, i), 1, 2};
      std::vector<std::uint8_t> bytes;
      encode_revolution(r, bytes);
      if (corrupt_.exchange(false)) bytes[1000] ^= 0x5a;
      if (split_) {
        handler_(std::span(bytes).first(700), hal::monotonic_now());
        handler_(std::span(bytes).subspan(700), hal::monotonic_now());
      } else {
        handler_(bytes, hal::monotonic_now());
      }
    }
  }

  double count_at_start_us_;
  double rate_;
  hal::Duration period_;
  hal::Timestamp started_;
  EventHandler events_;
  DataHandler handler_;
  std::thread thread_;
  std::mutex thread_mutex_;  // guards thread_ and handler_
  std::mutex mutex_;
  std::vector<hal::Timestamp> index_times_;
  std::uint32_t sequence_ = 0;
  std::atomic<bool> present_{true}, open_{false}, streaming_{false}, stalled_{false};
  std::atomic<bool> corrupt_{false}, skip_{false}, stall_{false}, split_{false};
  std::atomic<int> opens_{0};
};

}  // namespace rangefit::drivers::css_usb::test
