#include "daemon/cell/real_devices.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>

#include "daemon/cell/scan_loop.hpp"
#include "drivers/can/socketcan_transport.hpp"
#include "drivers/usb/css_usb_driver.hpp"
#include "drivers/usb/libusb_transport.hpp"
#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"

namespace rangefit::daemon {
namespace {

// Ok when both the sensor and the device moving it can deliver data now; otherwise why not,
// naming the first that cannot.
hal::Status usable(const std::string& a, const hal::Device& da, const std::string& b,
                   const hal::Device& db) {
  for (const auto& [name, dev] : {std::pair{&a, &da}, {&b, &db}}) {
    const hal::DeviceHealth h = dev->health();
    if (h.state == hal::DeviceState::kReady || h.state == hal::DeviceState::kStreaming) continue;
    return hal::Status::Error(*name + " not available (" + hal::to_string(h.state) +
                              (h.message.empty() ? "" : ": " + h.message) + ")");
  }
  return {};
}

// A sweep the daemon only watches starts now: what both streams queued before is dropped.
template <class A, class B>
void drop_stale(hal::SampleSource<A>& a, hal::SampleSource<B>& b) {
  std::vector<A> stale_a;
  std::vector<B> stale_b;
  a.read(stale_a, hal::Duration::zero());
  b.read(stale_b, hal::Duration::zero());
}

std::unique_ptr<drivers::can::CanTransport> socketcan(const std::string& interface,
                                                      drivers::can::FrameFilter filter) {
  drivers::can::SocketCanConfig c;
  c.interface = interface;
  c.filter = std::move(filter);
  return std::make_unique<drivers::can::SocketCanTransport>(c);
}

std::unique_ptr<hal::Device> make_driver(const DeviceConfig& d, const CellConfig& config,
                                         hal::Clock& clock) {
  if (d.kind == "axis") {
    return std::make_unique<drivers::FhppAxis>(
        fhpp_axis_config(d, config.fusion.stripe_cell.geometry.axis_travel_mm));
  }
  if (d.kind == "robot" && d.protocol == JointProtocol::kPowerCube) {
    const auto c = robot_powercube_config(d, config.fusion.css.joint);
    return std::make_unique<drivers::can::PowerCubeJointSource>(
        c, socketcan(d.transport, drivers::can::powercube_filter(c)));
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

// healthy(&why) for a scan loop: false when the sensor or the device moving it lost its link or
// faulted, *why naming which.
auto health_watch(const std::string& a, const hal::Device& da, const std::string& b,
                  const hal::Device& db) {
  return [&a, &da, &b, &db](std::string* why) {
    for (const auto& [name, dev] : {std::pair{&a, &da}, {&b, &db}}) {
      const hal::DeviceHealth h = dev->health();
      if (h.state == hal::DeviceState::kDisconnected || h.state == hal::DeviceState::kFault) {
        *why = *name + ": " + (h.message.empty() ? hal::to_string(h.state) : h.message);
        return false;
      }
    }
    return true;
  };
}

ScanOutcome failed(const DeviceConfig& device, const std::string& why) {
  return {hal::Status::Error(device.name + ": " + why), {}};
}

}  // namespace

RealDevices::RealDevices(const CellConfig& config)
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
  if (hal::Status s = usable(device.name, *ranger, axis_name, *axis); !s) return {s, {}};
  const fusion::StripeCellFusionConfig& fc = config_.fusion.stripe_cell;
  double from = 0.0, to = fc.geometry.axis_travel_mm;
  if (request.sweep_start != request.sweep_end) {
    from = request.sweep_start;
    to = request.sweep_end;
  }
  const double speed = request.sweep_speed > 0.0 ? request.sweep_speed : fc.geometry.max_speed_mm_s;
  fusion::StripeCellAssembler assembler(fc);
  hal::Status st = axis->enable();
  if (st) st = axis->move_to(from, fc.geometry.max_speed_mm_s);
  if (!st) return failed(device, axis_name + ": " + st.message);
  const auto start_sweep = [&](std::string* w) {
    assembler.begin_scan();
    const hal::Status s = axis->move_to(to, speed);
    if (!s) *w = axis_name + ": " + s.message;
    return static_cast<bool>(s);
  };
  const ScanLoopEnd end = sweep_stripe(*axis, *ranger, assembler, {cancel, progress}, start_sweep,
                                       health_watch(device.name, *ranger, axis_name, *axis), &why);
  if (end == ScanLoopEnd::kCancelled) {
    // The operator must know when the axis could not be stopped: it may still be moving.
    if (const hal::Status halted = axis->halt(); !halted) why += "; halt failed: " + halted.message;
  }
  if (end != ScanLoopEnd::kDone) return failed(device, why);
  return finish_scan(device, assembler.finish(), Eigen::Isometry3d::Identity(),
                     stripe_sensor(fc.geometry, from, to), clock_.get());
}

ScanOutcome RealDevices::scan_css(const DeviceConfig& device, const ScanRequest& request,
                                  const std::atomic<bool>& cancel,
                                  const std::function<void()>& progress) {
  std::string why;
  auto* joints = dynamic_cast<hal::JointSource*>(motion_of(device, "robot", &why));
  auto* css = dynamic_cast<hal::CssSource*>(devices_.at(device.name).get());
  if (joints == nullptr || css == nullptr) return {hal::Status::Error(why), {}};
  const std::string robot_name = joints->name();
  if (hal::Status s = usable(device.name, *css, robot_name, *joints); !s) return {s, {}};
  fusion::CssFusionConfig fc = config_.fusion.css;
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
      *css, *joints, {cancel, progress}, [&] { return sweep.at_end; }, fuse,
      health_watch(device.name, *css, robot_name, *joints), &why);
  if (end != ScanLoopEnd::kDone) return failed(device, why);
  return finish_scan(device, assembler.finish(), Eigen::Isometry3d::Identity(),
                     css_sensor(fc.geometry), clock_.get());
}

ScanOutcome RealDevices::scan_pan_tilt(const DeviceConfig& device, const ScanRequest& request,
                                       const std::atomic<bool>& cancel,
                                       const std::function<void()>& progress) {
  const std::string head_name = pan_tilt_angles_name(device.name);
  auto* ranger = dynamic_cast<hal::RangerSource*>(devices_.at(device.name).get());
  auto* head = dynamic_cast<hal::PanTiltSource*>(devices_.at(head_name).get());
  if (hal::Status s = usable(device.name, *ranger, head_name, *head); !s) return {s, {}};
  fusion::PanTiltFusionConfig fc = config_.fusion.pan_tilt;
  if (request.sweep_start != request.sweep_end) {
    fc.geometry.sweep_angle_rad = std::abs(request.sweep_end - request.sweep_start);
  }
  fusion::PanTiltAssembler assembler(fc);
  assembler.begin_scan();
  // Like the CSS: records while the cell program pans the head from -half to +half about
  // pan_zero (eq. 5.7); what arrived before the request is dropped first.
  drop_stale(*ranger, *head);
  SweepEdges sweep{0.5 * fc.geometry.sweep_angle_rad};
  const auto fuse = [&](const std::vector<hal::PanTiltSample>& angles,
                        const std::vector<hal::RangerProfile>& profiles) {
    for (const auto& a : angles) {
      sweep.see(a.pan_rad - fc.geometry.pan_zero_rad);
      assembler.add_pan_tilt(a);
    }
    for (const auto& p : profiles) assembler.add_profile(p);
  };
  std::string why;
  const ScanLoopEnd end = run_scan_loop(
      *head, *ranger, {cancel, progress}, [&] { return sweep.at_end; }, fuse,
      health_watch(device.name, *ranger, head_name, *head), &why);
  if (end != ScanLoopEnd::kDone) return failed(device, why);
  // The real head's tilt is held by the cell program; its zero is the calibrated pose.
  return finish_scan(
      device, assembler.finish(), Eigen::Isometry3d::Identity(),
      pan_tilt_sensor(fc.geometry, 0.5 * fc.geometry.sweep_angle_rad, fc.geometry.tilt_zero_rad),
      clock_.get());
}

}  // namespace rangefit::daemon
