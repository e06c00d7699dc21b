#pragma once
// The simulated Circular Scanning Sensor as a real USB device: a configfs gadget with one
// FunctionFS function on the dummy_hcd UDC (HIL VM, test/hil/run_vm.sh), speaking the CSS protocol
// of docs/protocols/css_usb.md. An ep0 reader thread answers GET_INFO, START, STOP, SET_RATE and
// GET_TIME; a stream thread writes one revolution per bulk IN transfer, paced by the device's own
// (offset, drifting, possibly 32-bit) µs counter at the rate SET_RATE asked for, so a test runs the
// device faster than real time by asking for more revolutions per second. Faults are injected on
// command, and the host time of every index pulse is kept as ground truth. Needs root.

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "test/hil/css_gadget/device_model.hpp"

namespace rangefit::hil {

struct CssGadgetOptions {
  std::uint16_t vendor_id = 0x1d6b;  // the driver's LibusbOptions default
  std::uint16_t product_id = 0x0105;
  std::string name = "css";  // configfs gadget and FunctionFS instance name
  std::string udc;           // empty: the first one in /sys/class/udc
  std::string serial = "CSS-SIM-0001";
  std::string scene_path;  // empty: synthetic pattern (RevolutionSource)
  DeviceClockModel clock;
  std::uint16_t rate_centi_hz = 700;  // until the host sends SET_RATE
  // A sensor on a moving cell (test/hil/cell_peer): what revolution `index` (counted from the
  // index pulse at host time pulse_origin) measured; false = laser off (no returns). The index
  // pulses then stay on that timeline across STOP/START and replugs, as a spinning motor's do.
  // Empty: the scene's scan of scene_path, revolution = sequence.
  using Revolution =
      std::function<bool(std::uint64_t index, std::array<drivers::css_usb::WireSample,
                                                         drivers::css_usb::kSamples>& samples)>;
  Revolution revolution;
  hal::Timestamp pulse_origin{};
};

// Faults, each applied to the next revolution(s) the stream thread sends.
enum class Fault {
  kStall,     // halt the bulk IN endpoint before the next frame (the host must clear it)
  kTruncate,  // send only the first 1000 bytes of a frame: that revolution is lost
  kSplit,     // send a frame as two short transfers (700 + 1376 bytes): nothing is lost
  kBadCrc,    // flip a sample byte after the CRC was computed
  kGap,       // skip one sequence number
};

class CssGadget {
 public:
  explicit CssGadget(CssGadgetOptions options);
  ~CssGadget();
  CssGadget(const CssGadget&) = delete;
  CssGadget& operator=(const CssGadget&) = delete;

  // Creates the gadget, writes the descriptors and binds the UDC. Empty string on success,
  // otherwise what failed (e.g. not root, modules missing).
  std::string start();
  // Cable pull and plug-in: unbind and rebind the UDC (the process and its sequence live on).
  bool unplug();
  bool replug();
  void inject(Fault fault);

  // Ground truth: host CLOCK_MONOTONIC of the index pulse of revolution `sequence`, if sent.
  std::optional<hal::Timestamp> truth(std::uint32_t sequence) const;
  const RevolutionSource& source() const { return source_; }
  const DeviceClockModel& clock() const { return options_.clock; }
  // Revolutions written completely; whether START is in force; the rate; STARTs received.
  std::uint64_t frames_sent() const { return frames_sent_; }
  bool streaming() const { return streaming_; }
  std::uint16_t rate_centi_hz() const { return rate_; }
  std::uint64_t starts() const { return starts_; }

 private:
  void ep0_loop();
  void handle_setup(const void* request);
  void stream_loop();
  bool send(const std::uint8_t* data, std::size_t size);
  void teardown();

  CssGadgetOptions options_;
  RevolutionSource source_;
  std::string gadget_dir_, mount_dir_, udc_;
  int ep0_ = -1, ep1_ = -1;
  bool mounted_ = false;

  std::atomic<bool> running_{false};
  std::atomic<bool> streaming_{false};
  std::atomic<std::uint16_t> rate_;
  std::atomic<std::uint64_t> frames_sent_{0}, starts_{0};
  std::atomic<int> stall_{0}, truncate_{0}, split_{0}, bad_crc_{0}, gap_{0};

  mutable std::mutex mutex_;  // truth_, start_host_, wake-ups of the stream thread
  std::condition_variable wake_;
  std::map<std::uint32_t, hal::Timestamp> truth_;
  std::uint64_t generation_ = 0;  // bumped by START and by the host going away
  std::uint32_t sequence_ = 0;
  std::thread ep0_thread_, stream_thread_;
};

}  // namespace rangefit::hil
