// kind = "css", driver = "real": the CSS on USB (drivers::css_usb::CssUsbDriver over
// LibusbTransport, transport "usb" or "usb:VID:PID" in hex). It records while the robot program
// pivots the last joint through -delta .. +delta (eq. 4.21; the daemon does not command the
// robot), the joint read from the robot device that moves it; bounded by service.scan_timeout_s.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "daemon/cell/real_devices.hpp"
#include "daemon/cell/real_sensor.hpp"
#include "drivers/usb/css_usb_driver.hpp"
#include "drivers/usb/libusb_transport.hpp"
#include "fusion/css_assembler.hpp"

namespace rangefit::daemon::real_sensors {
namespace {

std::vector<NamedDriver> css_drivers(const DeviceConfig& d, const CellConfig&, hal::Clock&) {
  drivers::css_usb::LibusbOptions usb;
  unsigned vid = 0, pid = 0;
  if (d.transport.rfind("usb:", 0) == 0 &&
      std::sscanf(d.transport.c_str() + 4, "%x:%x", &vid, &pid) == 2) {
    usb.vendor_id = static_cast<std::uint16_t>(vid);
    usb.product_id = static_cast<std::uint16_t>(pid);
  } else if (d.transport != "usb") {
    throw std::runtime_error("device " + d.name + ": transport: must be \"usb\" or " +
                             "\"usb:VID:PID\" (hex), got \"" + d.transport + "\"");
  }
  drivers::css_usb::CssUsbOptions o;
  o.name = d.name;
  std::vector<NamedDriver> out;
  out.push_back({d.name, std::make_unique<drivers::css_usb::CssUsbDriver>(
                             std::make_unique<drivers::css_usb::LibusbTransport>(usb), o)});
  return out;
}

ScanOutcome css_scan(RealDevices& cell, const DeviceConfig& device, const ScanRequest& request,
                     ScanControl control) {
  std::string why;
  auto* joints = cell.motion_as<hal::JointSource>(device, &why);
  auto* css = joints ? cell.driver_as<hal::CssSource>(device.name, &why) : nullptr;
  if (css == nullptr) return {hal::Status::Error(why), {}};
  const std::string robot_name = joints->name();
  if (hal::Status s = usable(device.name, *css, robot_name, *joints); !s) return {s, {}};
  fusion::CssFusionConfig fc = cell.config().fusion.css;
  if (request.sweep_start != request.sweep_end) {
    fc.deflection_rad = 0.5 * std::abs(request.sweep_end - request.sweep_start);
  }
  fusion::CssAssembler assembler(fc);
  assembler.begin_scan();
  // Records while the robot program pivots the joint from -delta to +delta (eq. 4.21); stale
  // data from before the request is dropped first.
  drop_stale(*css, *joints);
  SweepEdges sweep{fc.deflection_rad};
  const auto fuse = [&](const std::vector<hal::CssRevolution>& revs,
                        const std::vector<hal::JointSample>& samples) {
    for (const auto& j : samples) {
      if (j.joint != fc.joint) continue;
      sweep.see(j.angle_rad - fc.omega_zero_rad);
      assembler.add_joint(j);
    }
    for (const auto& r : revs) assembler.add_revolution(r);
  };
  const ScanLoopEnd end = run_scan_loop(
      *css, *joints, control, [&] { return sweep.at_end; }, fuse,
      health_watch(device.name, *css, robot_name, *joints), &why);
  if (end != ScanLoopEnd::kDone) return failed(device, why);
  return finish_scan(device, assembler.finish(), Eigen::Isometry3d::Identity(),
                     css_sensor(fc.geometry, fc.omega_zero_rad), &cell.clock());
}

}  // namespace

extern const RealSensor css;
const RealSensor css{"css", css_drivers, css_scan};

}  // namespace rangefit::daemon::real_sensors
