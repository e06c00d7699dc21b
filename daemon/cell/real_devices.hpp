#pragma once
// driver = "real": the cell's drivers, built from each device's kind (its RealSensor,
// daemon/cell/sensors/<kind>.cpp) and transport:
//   axis     - drivers::FhppAxis (Festo FHPP over Modbus): "host:port" (TCP) or "/dev/tty..."
//              (RTU), unit modbus_unit (default 1);
//   robot    - drivers::can::Cia402JointSource (CiA 402 joints, SYNC master) on a SocketCAN
//              interface, e.g. "can0"; the CSS's last joint (fusion.css.joint) on node can_node
//              (default 1);
//   stripe   - drivers::can::RangerCanSource (node can_node, default 0x20) on a SocketCAN
//              interface;
//   css      - drivers::css_usb::CssUsbDriver over LibusbTransport: "usb" or "usb:VID:PID" (hex);
//   pan_tilt - the head's ranger (drivers::can::RangerCanSource, node can_node) and its pan/tilt
//              axes (drivers::can::Cia402PanTiltSource, nodes pan_node and tilt_node, default 1
//              and 2, reported as "<name>/angles") on one SocketCAN interface.
// daemon/driver_configs.hpp builds each driver's settings from the device's table.
// Every driver starts at construction and reconnects by itself, so a device that is absent at
// start is only reported (diagnostics ERROR via its health) and never fatal; a request that needs
// it is answered with an error naming the device and its state.
//
// Scans: a stripe device sweeps with its `motion` axis (or the only axis) exactly like the
// simulated cell, and several stripe devices on one axis (the cameras of one laser plane) sweep
// together; a css device records while the robot program pivots the last joint through
// -delta .. +delta (the daemon does not command the robot) and is bounded by
// service.scan_timeout_s; a pan_tilt device likewise records while the cell program pans the
// head through the sweep (the daemon does not command the pan-tilt unit).

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "daemon/cell/cell_devices.hpp"
#include "daemon/cell/driver_configs.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/pipeline.hpp"
#include "hal/source.hpp"

namespace rangefit::daemon {

class RealDevices final : public CellDevices {
 public:
  // Builds and starts every driver = "real" device; throws std::runtime_error on a transport
  // string that cannot be understood (a config error, so at start-up or reload only).
  explicit RealDevices(const CellConfig& config);
  ~RealDevices();
  RealDevices(const RealDevices&) = delete;
  RealDevices& operator=(const RealDevices&) = delete;

  ScanOutcome scan(const DeviceConfig& device, const ScanRequest& request,
                   const std::atomic<bool>& cancel, const std::function<void()>& progress) override;
  // Devices their kind scans together (stripe: one axis; pan_tilt: one head).
  std::vector<ScanOutcome> scan_together(std::span<const DeviceConfig* const> devices,
                                         const ScanRequest& request,
                                         const std::atomic<bool>& cancel,
                                         const std::function<void()>& progress) override;
  std::vector<NamedHealth> health() const override;

  // What the kinds' scans (daemon/cell/sensors/) reach: the configuration, the drivers' clock,
  // a driver by its health name and the device that moves `device` (its `motion` field, else
  // the only real device of the kind that moves it, SensorKind::moved_by), each as the
  // interface T the scan drives (hal::RangerSource, hal::LinearAxis, ...). Null with *why when
  // there is none, several, or it is not a T, so a scan never casts.
  const CellConfig& config() const { return config_; }
  hal::Clock& clock() const { return *clock_; }
  template <class T>
  T* driver_as(const std::string& name, std::string* why) const {
    const auto it = devices_.find(name);
    T* typed = it == devices_.end() ? nullptr : dynamic_cast<T*>(it->second.get());
    if (typed == nullptr) *why = name + ": no real driver of the interface its scan needs";
    return typed;
  }
  template <class T>
  T* motion_as(const DeviceConfig& device, std::string* why) const {
    hal::Device* motion = motion_of(device, why);
    T* typed = dynamic_cast<T*>(motion);
    if (motion != nullptr && typed == nullptr) {
      *why = device.name + ": " + motion->name() + " cannot move it";
    }
    return typed;
  }

 private:
  hal::Device* motion_of(const DeviceConfig& device, std::string* why) const;

  CellConfig config_;
  std::unique_ptr<hal::Clock> clock_;  // CLOCK_MONOTONIC, shared by the drivers that take one
  std::map<std::string, std::unique_ptr<hal::Device>> devices_;  // by health name
  std::map<std::string, std::vector<std::string>> drivers_of_;   // health names, by config name
};

}  // namespace rangefit::daemon
