#include "daemon/real_devices.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>

#include "daemon/sim_cell.hpp"
#include "drivers/can/socketcan_transport.hpp"
#include "drivers/usb/css_usb_driver.hpp"
#include "drivers/usb/libusb_transport.hpp"
#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"

namespace rangefit::daemon {
namespace {

using std::chrono::milliseconds;
constexpr hal::Duration kReadSlice = milliseconds(100);

// Ok when the device can deliver data now; otherwise why not, naming it.
hal::Status usable(const std::string& name, const hal::Device& d) {
  const hal::DeviceHealth h = d.health();
  if (h.state == hal::DeviceState::kReady || h.state == hal::DeviceState::kStreaming) return {};
  return hal::Status::Error(name + " not available (" + hal::to_string(h.state) +
                            (h.message.empty() ? "" : ": " + h.message) + ")");
}

std::unique_ptr<drivers::can::CanTransport> socketcan(const std::string& interface,
                                                      drivers::can::FrameFilter filter) {
  drivers::can::SocketCanConfig c;
  c.interface = interface;
  c.filter = std::move(filter);
  return std::make_unique<drivers::can::SocketCanTransport>(c);
}

std::unique_ptr<hal::Device> make_driver(const DeviceConfig& d, const DaemonConfig& config,
                                         hal::Clock& clock) {
  if (d.kind == "axis") {
    return std::make_unique<drivers::FhppAxis>(
        fhpp_axis_config(d, config.fusion.stripe_cell.geometry.axis_travel_mm));
  }
  if (d.kind == "robot") {
    const auto c = robot_joint_config(d, config.fusion.css.joint);
    return std::make_unique<drivers::can::Cia402JointSource>(
        c, socketcan(d.transport, drivers::can::cia402_filter(c)));
  }
  if (d.kind == "stripe" || d.kind == "pan_tilt") {  // the head's ranger; its angles: below
    const auto c = ranger_config(d);
    return std::make_unique<drivers::can::RangerCanSource>(
        c, socketcan(d.transport, drivers::can::ranger_filter(c)));
  }
  if (d.kind == "css") {
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
    return std::make_unique<drivers::css_usb::CssUsbDriver>(
        std::make_unique<drivers::css_usb::LibusbTransport>(usb), o, clock);
  }
  return nullptr;
}

// The pan-tilt head's second driver: its pan and tilt axes (two CiA 402 nodes on the ranger's bus).
std::unique_ptr<hal::Device> make_pan_tilt_angles(const DeviceConfig& d) {
  const auto c = pan_tilt_config(d);
  return std::make_unique<drivers::can::Cia402PanTiltSource>(
      c, socketcan(d.transport, drivers::can::cia402_filter(drivers::can::pan_tilt_bus_config(c))));
}

// Fails when the sensor or the device moving it lost its link or faulted.
bool watch(const std::string& a, const hal::Device& da, const std::string& b, const hal::Device& db,
           std::string* why) {
  for (const auto& [name, dev] : {std::pair{&a, &da}, {&b, &db}}) {
    const hal::DeviceHealth h = dev->health();
    if (h.state == hal::DeviceState::kDisconnected || h.state == hal::DeviceState::kFault) {
      *why = *name + ": " + (h.message.empty() ? hal::to_string(h.state) : h.message);
      return false;
    }
  }
  return true;
}

ScanOutcome finish(const DeviceConfig& device, fusion::FusedScan scan) {
  if (scan.bad) return {hal::Status::Error(device.name + ": fusion: " + scan.reason), {}};
  const Eigen::Isometry3d T = device_extrinsics(device);
  for (auto& p : scan.cloud.points) p = T * p;
  for (auto& n : scan.cloud.normals) n = T.linear() * n;
  return {hal::Status::Ok(), std::move(scan.cloud)};
}

}  // namespace

RealDevices::RealDevices(const DaemonConfig& config)
    : config_(config), clock_(std::make_unique<hal::MonotonicClock>()) {
  for (const auto& d : config_.devices) {
    if (d.driver != DriverKind::kReal) continue;
    std::vector<std::pair<std::string, std::unique_ptr<hal::Device>>> drivers;
    drivers.emplace_back(d.name, make_driver(d, config_, *clock_));
    if (d.kind == "pan_tilt")
      drivers.emplace_back(pan_tilt_angles_name(d.name), make_pan_tilt_angles(d));
    for (auto& [name, driver] : drivers) {
      if (!driver) continue;
      if (const hal::Status s = driver->start(); !s) {
        throw std::runtime_error("device " + name + ": " + s.message);
      }
      spdlog::info("device {}: {} driver on {} started", name, d.kind, d.transport);
      devices_[name] = std::move(driver);
    }
  }
}

RealDevices::~RealDevices() {
  for (auto& [name, d] : devices_) d->stop();
}

std::vector<NamedHealth> RealDevices::health() const {
  std::vector<NamedHealth> out;
  for (const auto& d : config_.devices) {
    if (d.driver != DriverKind::kReal) continue;
    const auto it = devices_.find(d.name);
    if (it != devices_.end()) {
      out.push_back({d.name, it->second->health()});
    } else {
      hal::DeviceHealth h;
      h.message = "no real driver for kind " + d.kind + " in this build";
      out.push_back({d.name, h});
    }
    if (const auto a = devices_.find(pan_tilt_angles_name(d.name)); a != devices_.end()) {
      out.push_back({a->first, a->second->health()});
    }
  }
  return out;
}

hal::Device* RealDevices::motion_of(const DeviceConfig& device, const std::string& kind,
                                    std::string* why) const {
  std::string name = device.motion;
  if (name.empty()) {
    for (const auto& d : config_.devices) {
      if (d.kind != kind || d.driver != DriverKind::kReal) continue;
      if (!name.empty()) {
        *why = device.name + ": several " + kind + " devices; set devices.motion";
        return nullptr;
      }
      name = d.name;
    }
  }
  const auto it = devices_.find(name);
  if (name.empty() || it == devices_.end()) {
    *why = device.name + ": no real " + kind + " device moves it (devices.motion)";
    return nullptr;
  }
  return it->second.get();
}

ScanOutcome RealDevices::scan(const DeviceConfig& device, const ScanRequest& request,
                              const std::atomic<bool>& cancel,
                              const std::function<void()>& progress) {
  if (device.kind == "stripe") return scan_stripe(device, request, cancel, progress);
  if (device.kind == "css") return scan_css(device, request, cancel, progress);
  if (device.kind == "pan_tilt") return scan_pan_tilt(device, request, cancel, progress);
  return {hal::Status::Error("device " + device.name + " (kind " + device.kind +
                             ") cannot scan with driver = \"real\" in this build"),
          {}};
}

ScanOutcome RealDevices::scan_stripe(const DeviceConfig& device, const ScanRequest& request,
                                     const std::atomic<bool>& cancel,
                                     const std::function<void()>& progress) {
  std::string why;
  auto* axis = dynamic_cast<hal::LinearAxis*>(motion_of(device, "axis", &why));
  auto* ranger = dynamic_cast<hal::RangerSource*>(devices_.at(device.name).get());
  if (axis == nullptr || ranger == nullptr) return {hal::Status::Error(why), {}};
  const std::string axis_name = axis->name();
  for (const auto& [name, d] :
       {std::pair<std::string, hal::Device*>{device.name, ranger}, {axis_name, axis}}) {
    if (hal::Status s = usable(name, *d); !s) return {s, {}};
  }
  const fusion::StripeCellFusionConfig& fc = config_.fusion.stripe_cell;
  double from = 0.0, to = fc.geometry.axis_travel_mm;
  if (request.sweep_start != request.sweep_end) {
    from = request.sweep_start;
    to = request.sweep_end;
  }
  const double speed = request.sweep_speed > 0.0 ? request.sweep_speed : fc.geometry.max_speed_mm_s;
  fusion::StripeCellAssembler assembler(fc);
  std::vector<hal::RangerProfile> profiles;
  std::vector<hal::AxisSample> samples;
  hal::Status st = axis->enable();
  if (st) st = axis->move_to(from, fc.geometry.max_speed_mm_s);
  bool ok = static_cast<bool>(st);
  if (!st) why = axis_name + ": " + st.message;
  for (int leg = 0; ok && leg < 2; ++leg) {
    if (leg == 1) {
      assembler.begin_scan();
      if (st = axis->move_to(to, speed); !st) {
        why = axis_name + ": " + st.message;
        ok = false;
      }
    }
    while (ok && !axis->motion_complete()) {
      if (cancel) {
        why = "cancelled";
        axis->halt();
        ok = false;
        break;
      }
      profiles.clear();
      samples.clear();
      axis->read(samples, kReadSlice);
      ranger->read(profiles, hal::Duration::zero());
      if (leg == 1) {
        for (const auto& s : samples) assembler.add_axis(s);
        for (const auto& p : profiles) assembler.add_profile(p);
      }
      if (!samples.empty() || !profiles.empty()) progress();
      ok = watch(device.name, *ranger, axis_name, *axis, &why);
    }
  }
  if (!ok) return {hal::Status::Error(device.name + ": " + why), {}};
  return finish(device, assembler.finish());
}

ScanOutcome RealDevices::scan_css(const DeviceConfig& device, const ScanRequest& request,
                                  const std::atomic<bool>& cancel,
                                  const std::function<void()>& progress) {
  std::string why;
  auto* joints = dynamic_cast<hal::JointSource*>(motion_of(device, "robot", &why));
  auto* css = dynamic_cast<hal::CssSource*>(devices_.at(device.name).get());
  if (joints == nullptr || css == nullptr) return {hal::Status::Error(why), {}};
  const std::string robot_name = joints->name();
  for (const auto& [name, d] :
       {std::pair<std::string, hal::Device*>{device.name, css}, {robot_name, joints}}) {
    if (hal::Status s = usable(name, *d); !s) return {s, {}};
  }
  fusion::CssFusionConfig fc = config_.fusion.css;
  if (request.sweep_start != request.sweep_end) {
    fc.deflection_rad = 0.5 * std::abs(request.sweep_end - request.sweep_start);
  }
  fusion::CssAssembler assembler(fc);
  assembler.begin_scan();
  std::vector<hal::CssRevolution> revs;
  std::vector<hal::JointSample> samples;
  // Records while the robot program pivots the joint from -delta to +delta (eq. 4.21); stale
  // data from before the request is dropped first.
  css->read(revs, hal::Duration::zero());
  joints->read(samples, hal::Duration::zero());
  constexpr double kSlack = 1e-4;  // rad
  bool at_start = false, at_end = false, ok = true;
  while (ok && !at_end) {
    if (cancel) {
      why = "cancelled";
      ok = false;
      break;
    }
    revs.clear();
    samples.clear();
    css->read(revs, kReadSlice);
    joints->read(samples, hal::Duration::zero());
    for (const auto& j : samples) {
      if (j.joint != fc.joint) continue;
      const double omega = j.angle_rad - fc.omega_zero_rad;
      at_start = at_start || omega <= -fc.deflection_rad + kSlack;
      at_end = at_start && omega >= fc.deflection_rad - kSlack;
      assembler.add_joint(j);
    }
    for (const auto& r : revs) assembler.add_revolution(r);
    if (!revs.empty() || !samples.empty()) progress();
    ok = watch(device.name, *css, robot_name, *joints, &why);
  }
  if (!ok) return {hal::Status::Error(device.name + ": " + why), {}};
  return finish(device, assembler.finish());
}

ScanOutcome RealDevices::scan_pan_tilt(const DeviceConfig& device, const ScanRequest& request,
                                       const std::atomic<bool>& cancel,
                                       const std::function<void()>& progress) {
  const std::string head_name = pan_tilt_angles_name(device.name);
  auto* ranger = dynamic_cast<hal::RangerSource*>(devices_.at(device.name).get());
  auto* head = dynamic_cast<hal::PanTiltSource*>(devices_.at(head_name).get());
  for (const auto& [name, d] :
       {std::pair<std::string, hal::Device*>{device.name, ranger}, {head_name, head}}) {
    if (hal::Status s = usable(name, *d); !s) return {s, {}};
  }
  fusion::PanTiltFusionConfig fc = config_.fusion.pan_tilt;
  if (request.sweep_start != request.sweep_end) {
    fc.geometry.sweep_angle_rad = std::abs(request.sweep_end - request.sweep_start);
  }
  const double half = 0.5 * fc.geometry.sweep_angle_rad;
  fusion::PanTiltAssembler assembler(fc);
  assembler.begin_scan();
  std::vector<hal::RangerProfile> profiles;
  std::vector<hal::PanTiltSample> angles;
  // Like the CSS: records while the cell program pans the head from -half to +half about
  // pan_zero (eq. 5.7); what arrived before the request is dropped first.
  ranger->read(profiles, hal::Duration::zero());
  head->read(angles, hal::Duration::zero());
  constexpr double kSlack = 1e-4;  // rad
  bool at_start = false, at_end = false, ok = true;
  std::string why;
  while (ok && !at_end) {
    if (cancel) {
      why = "cancelled";
      ok = false;
      break;
    }
    profiles.clear();
    angles.clear();
    head->read(angles, kReadSlice);
    ranger->read(profiles, hal::Duration::zero());
    for (const auto& a : angles) {
      const double pan = a.pan_rad - fc.geometry.pan_zero_rad;
      at_start = at_start || pan <= -half + kSlack;
      at_end = at_start && pan >= half - kSlack;
      assembler.add_pan_tilt(a);
    }
    for (const auto& p : profiles) assembler.add_profile(p);
    if (!angles.empty() || !profiles.empty()) progress();
    ok = watch(device.name, *ranger, head_name, *head, &why);
  }
  if (!ok) return {hal::Status::Error(device.name + ": " + why), {}};
  return finish(device, assembler.finish());
}

}  // namespace rangefit::daemon
