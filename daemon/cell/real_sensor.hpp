#pragma once
// driver = "real": what differs per kind of device. Each file of daemon/cell/sensors/ registers
// one RealSensor (docs/adding_a_sensor.md): the drivers a device of its kind runs and, for a
// kind that scans, how it scans with them. RealDevices looks them up by the device's kind.
// The helpers below are what the kinds' scans share.

#include <atomic>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "daemon/cell/scan_loop.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/pipeline.hpp"
#include "drivers/can/transport.hpp"
#include "hal/source.hpp"
#include "hal/stripe_geometry.hpp"

namespace rangefit::daemon {

class RealDevices;

// A driver of a device and the name its health is reported under.
struct NamedDriver {
  std::string name;
  std::unique_ptr<hal::Device> driver;
};

struct RealSensor {
  const char* kind;  // SensorKind::name of the kind it drives
  // The device's drivers, its own name first (not started). Throws std::runtime_error on a
  // transport the driver cannot use (a config error).
  std::vector<NamedDriver> (*make_drivers)(const DeviceConfig& d, const CellConfig& config,
                                           hal::Clock& clock);
  // Scans with the device (its drivers are in `cell`); null: the kind takes no scans.
  ScanOutcome (*scan)(RealDevices& cell, const DeviceConfig& d, const ScanRequest& request,
                      ScanControl control);
  // Scans with several devices of the kind in one motion, one outcome each in order; empty when
  // they do not share their motion device (RealDevices checks the kind and configured sweep).
  // Null: one at a time.
  std::vector<ScanOutcome> (*scan_together)(RealDevices& cell,
                                            std::span<const DeviceConfig* const> devices,
                                            const ScanRequest& request,
                                            ScanControl control) = nullptr;
};

// Every registered RealSensor, in name order (generated from the files of daemon/cell/sensors).
std::span<const RealSensor* const> all_real_sensors();
// The RealSensor of that kind; null when this build has none.
const RealSensor* find_real_sensor(const DeviceKind& kind);

// Ok when both the sensor and the device moving it can deliver data now; otherwise why not,
// naming the first that cannot.
hal::Status usable(const std::string& a, const hal::Device& da, const std::string& b,
                   const hal::Device& db);

// healthy(&why) for a scan loop: false when the sensor or the device moving it lost its link or
// faulted, *why naming which.
std::function<bool(std::string*)> health_watch(const std::string& a, const hal::Device& da,
                                               const std::string& b, const hal::Device& db);

// A sweep the daemon only watches starts now: what both streams queued before is dropped.
template <class A, class B>
void drop_stale(hal::SampleSource<A>& a, hal::SampleSource<B>& b) {
  std::vector<A> stale_a;
  std::vector<B> stale_b;
  a.read(stale_a, hal::Duration::zero());
  b.read(stale_b, hal::Duration::zero());
}

ScanOutcome failed(const DeviceConfig& device, const std::string& why);

// The same outcome for every device of a shared sweep: it failed for all of them.
std::vector<ScanOutcome> all_failed(std::span<const DeviceConfig* const> devices,
                                    const hal::Status& status);

// healthy(&why) for a scan loop over several sensors: false at the first watch that says so.
std::function<bool(std::string*)> all_healthy(
    std::vector<std::function<bool(std::string*)>> watches);

// A SocketCAN transport on `interface` receiving what `filter` passes; fd: CAN FD frames too.
std::unique_ptr<drivers::can::CanTransport> socketcan(const std::string& interface,
                                                      drivers::can::FrameFilter filter,
                                                      bool fd = false);

// The laser-stripe ranger of a stripe or pan_tilt device (node can_node on its CAN FD
// interface), its columns on the fan rays of `geometry`: the cell's or the head's ranger.
std::unique_ptr<hal::Device> ranger_driver(const DeviceConfig& d,
                                           const hal::StripeRanger& geometry);

}  // namespace rangefit::daemon
