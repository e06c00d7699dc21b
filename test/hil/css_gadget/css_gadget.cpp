#include "test/hil/css_gadget/css_gadget.hpp"

#include <fcntl.h>
#include <linux/usb/ch9.h>
#include <linux/usb/functionfs.h>
#include <poll.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "hal/samples.hpp"
#include "test/hil/css_gadget/ffs_setup.hpp"

namespace rangefit::hil {

namespace css = drivers::css_usb;

CssGadget::CssGadget(CssGadgetOptions options)
    : options_(std::move(options)), source_(options_.scene_path), rate_(options_.rate_centi_hz) {}

CssGadget::~CssGadget() { teardown(); }

std::string CssGadget::start() {
  std::string e = ffs::create_gadget(
      {options_.vendor_id, options_.product_id, options_.serial, options_.name}, gadget_dir_);
  if (!e.empty()) return e;
  mount_dir_ = "/run/ffs-" + options_.name;
  std::filesystem::create_directories(mount_dir_);
  ::umount(mount_dir_.c_str());  // a stale instance from an aborted run
  if (::mount(options_.name.c_str(), mount_dir_.c_str(), "functionfs", 0, nullptr) != 0) {
    return "mount functionfs: " + std::string(std::strerror(errno));
  }
  mounted_ = true;
  ep0_ = ::open((mount_dir_ + "/ep0").c_str(), O_RDWR);
  if (ep0_ < 0) return "open ep0: " + std::string(std::strerror(errno));
  // Descriptors and strings go to ep0 before the UDC is bound; ep1 appears after them.
  for (const auto& blob : {ffs::descriptors(), ffs::strings()}) {
    if (::write(ep0_, blob.data(), blob.size()) != static_cast<ssize_t>(blob.size())) {
      return "write ep0 descriptors: " + std::string(std::strerror(errno));
    }
  }
  // Non-blocking only affects waiting for the endpoint to be enabled (EAGAIN while unbound);
  // a write still returns once the host has taken the data.
  ep1_ = ::open((mount_dir_ + "/ep1").c_str(), O_RDWR | O_NONBLOCK);
  if (ep1_ < 0) return "open ep1: " + std::string(std::strerror(errno));
  running_ = true;
  ep0_thread_ = std::thread([this] { ep0_loop(); });
  stream_thread_ = std::thread([this] { stream_loop(); });
  udc_ = options_.udc.empty() ? ffs::first_udc() : options_.udc;
  if (udc_.empty()) return "no UDC in /sys/class/udc (dummy_hcd loaded?)";
  return replug() ? "" : "bind UDC " + udc_ + " failed";
}

bool CssGadget::unplug() { return ffs::write_text(gadget_dir_ + "/UDC", "\n").empty(); }
bool CssGadget::replug() { return ffs::write_text(gadget_dir_ + "/UDC", udc_).empty(); }

void CssGadget::teardown() {
  running_ = false;
  streaming_ = false;
  wake_.notify_all();
  // Unbinding ends a write the host is no longer reading and wakes the ep0 reader.
  if (!gadget_dir_.empty()) unplug();
  if (stream_thread_.joinable()) stream_thread_.join();
  if (ep0_thread_.joinable()) ep0_thread_.join();
  if (ep1_ >= 0) ::close(ep1_);
  if (ep0_ >= 0) ::close(ep0_);
  ep0_ = ep1_ = -1;
  if (mounted_) ::umount(mount_dir_.c_str());
  mounted_ = false;
  ffs::remove_gadget(gadget_dir_);
  gadget_dir_.clear();
}

void CssGadget::inject(Fault fault) {
  switch (fault) {
    case Fault::kStall:
      ++stall_;
      break;
    case Fault::kTruncate:
      ++truncate_;
      break;
    case Fault::kSplit:
      ++split_;
      break;
    case Fault::kBadCrc:
      ++bad_crc_;
      break;
    case Fault::kGap:
      ++gap_;
      break;
  }
}

std::optional<hal::Timestamp> CssGadget::truth(std::uint32_t sequence) const {
  std::lock_guard lock(mutex_);
  const auto it = truth_.find(sequence);
  if (it == truth_.end()) return std::nullopt;
  return it->second;
}

void CssGadget::ep0_loop() {
  usb_functionfs_event events[4];
  while (running_) {
    pollfd p{ep0_, POLLIN, 0};
    if (::poll(&p, 1, 50) <= 0) continue;
    const ssize_t n = ::read(ep0_, events, sizeof events);
    if (n <= 0) continue;
    for (std::size_t i = 0; i < static_cast<std::size_t>(n) / sizeof events[0]; ++i) {
      switch (events[i].type) {
        case FUNCTIONFS_SETUP:
          handle_setup(&events[i].u.setup);
          break;
        case FUNCTIONFS_DISABLE:
        case FUNCTIONFS_UNBIND: {
          // The host is gone (cable pulled): the sensor stops sending until the next START.
          std::lock_guard lock(mutex_);
          streaming_ = false;
          ++generation_;
          wake_.notify_all();
          break;
        }
        default:
          break;
      }
    }
  }
}

void CssGadget::handle_setup(const void* request) {
  usb_ctrlrequest setup;
  std::memcpy(&setup, request, sizeof setup);
  const bool in = (setup.bRequestType & USB_DIR_IN) != 0;
  const std::uint16_t length = le16toh(setup.wLength);
  const std::uint16_t value = le16toh(setup.wValue);
  std::uint8_t reply[css::kInfoBytes] = {};
  std::size_t reply_size = 0;
  bool ok = (setup.bRequestType & USB_TYPE_MASK) == USB_TYPE_VENDOR;
  switch (static_cast<css::Request>(setup.bRequest)) {
    case css::Request::kGetInfo: {
      css::DeviceInfo info;
      info.serial = options_.serial;
      info.firmware = 0x00010002;
      info.rate_centi_hz = rate_;
      const auto bytes = css::encode_info(info);
      std::memcpy(reply, bytes.data(), bytes.size());
      reply_size = bytes.size();
      ok = ok && in;
      break;
    }
    case css::Request::kGetTime: {
      // Read the counter as late as possible: the host places it at its exchange's midpoint.
      const std::uint64_t now = options_.clock.read(hal::monotonic_now());
      for (std::size_t i = 0; i < 8; ++i) reply[i] = static_cast<std::uint8_t>(now >> (8 * i));
      reply_size = 8;
      ok = ok && in;
      break;
    }
    case css::Request::kStart:
    case css::Request::kStop: {
      ok = ok && !in;
      if (!ok) break;
      std::lock_guard lock(mutex_);
      const bool start = setup.bRequest == static_cast<std::uint8_t>(css::Request::kStart);
      if (start) ++starts_;
      streaming_ = start;
      ++generation_;
      wake_.notify_all();
      break;
    }
    case css::Request::kSetRate:
      ok = ok && !in && value >= 10;  // below 0.1 rev/s the motor does not lock: refuse
      if (ok) rate_ = value;
      break;
    default:
      ok = false;
  }
  if (!ok) {
    // Stall the control request: FunctionFS stalls ep0 on I/O in the wrong direction.
    if (in) {
      [[maybe_unused]] ssize_t r = ::read(ep0_, reply, 0);
    } else {
      [[maybe_unused]] ssize_t r = ::write(ep0_, reply, 0);
    }
    return;
  }
  if (in) {
    [[maybe_unused]] ssize_t r = ::write(ep0_, reply, std::min<std::size_t>(reply_size, length));
  } else {
    [[maybe_unused]] ssize_t r = ::read(ep0_, reply, 0);  // status stage
  }
}

bool CssGadget::send(const std::uint8_t* data, std::size_t size) {
  while (running_ && streaming_) {
    const ssize_t n = ::write(ep1_, data, size);
    if (n == static_cast<ssize_t>(size)) break;
    if (n < 0 && errno == EAGAIN) {  // endpoint not enabled yet (host still configuring)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    return false;  // unbound mid-transfer, or the host cleared the stream
  }
  if (!running_ || !streaming_) return false;
  // A write of whole packets does not end the host's transfer: a zero-length packet does.
  if (size % 64 == 0) {
    [[maybe_unused]] ssize_t r = ::write(ep1_, data, 0);
  }
  return true;
}

void CssGadget::stream_loop() {
  std::vector<std::uint8_t> frame;
  css::WireRevolution r;
  while (running_) {
    std::unique_lock lock(mutex_);
    wake_.wait(lock, [&] { return !running_ || streaming_; });
    if (!running_) break;
    const std::uint64_t generation = generation_;
    lock.unlock();
    // START begins a pulse train at the device's current time, at the rate last set.
    const DeviceClockModel& clock = options_.clock;
    const double period_us = std::round(1e8 / rate_);
    double first_pulse_us = std::floor(clock.exact_us(hal::monotonic_now()));
    std::uint64_t first_index = 0;
    if (options_.revolution) {
      // The motor turns whether or not a host listens: pulses stay on the cell's timeline.
      const double origin_us = clock.exact_us(options_.pulse_origin);
      const double since = std::max(0.0, first_pulse_us - origin_us);
      first_index = static_cast<std::uint64_t>(std::ceil(since / period_us));
      first_pulse_us = origin_us + static_cast<double>(first_index) * period_us;
    }
    for (std::uint64_t k = 0;; ++k) {
      const double pulse_us = first_pulse_us + static_cast<double>(k) * period_us;
      // The frame leaves when the revolution is complete, i.e. at the next index pulse.
      lock.lock();
      const bool current = wake_.wait_until(
          lock, std::chrono::steady_clock::time_point(clock.host_time(pulse_us + period_us)),
          [&] { return !running_ || generation_ != generation; });
      if (current) break;  // stopped, restarted or unplugged
      if (gap_ > 0) {
        --gap_;
        ++sequence_;
      }
      r.sequence = sequence_++;
      truth_[r.sequence] = clock.host_time(pulse_us);
      lock.unlock();
      const std::uint64_t wrap_mask = clock.counter_bits >= 64
                                          ? ~std::uint64_t{0}
                                          : (std::uint64_t{1} << clock.counter_bits) - 1;
      r.device_time_us =
          static_cast<std::uint64_t>(static_cast<std::int64_t>(pulse_us)) & wrap_mask;
      r.period_us = static_cast<std::uint32_t>(period_us);
      r.flags = hal::kCssMotorLocked | hal::kCssLaserOn;
      if (options_.revolution) {
        if (!options_.revolution(first_index + k, r.samples)) r.flags = hal::kCssMotorLocked;
      } else {
        r.samples = source_.samples(r.sequence);
      }
      frame.clear();
      css::encode_revolution(r, frame);
      if (bad_crc_ > 0) {
        --bad_crc_;
        frame[1000] ^= 0x5a;
      }
      if (stall_ > 0) {
        // Between frames, so the stall loses nothing: the next write waits for CLEAR_FEATURE.
        --stall_;
        [[maybe_unused]] ssize_t n = ::read(ep1_, frame.data(), 1);
      }
      bool sent = false;
      if (truncate_ > 0) {
        --truncate_;
        sent = send(frame.data(), 1000);
      } else if (split_ > 0) {
        --split_;
        sent = send(frame.data(), 700) && send(frame.data() + 700, frame.size() - 700);
      } else {
        sent = send(frame.data(), frame.size());
      }
      if (sent) ++frames_sent_;
    }
  }
}

}  // namespace rangefit::hil
