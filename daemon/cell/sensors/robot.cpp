// kind = "robot", driver = "real": the CSS's last joint (fusion.css.joint) on a SocketCAN
// interface, e.g. "can0": drivers::can::Cia402JointSource (CiA 402, SYNC master) on node
// can_node (default 1), or with protocol = "powercube" drivers::can::PowerCubeJointSource
// (module can_node). It moves a css sensor and takes no scan itself.
#include "daemon/cell/driver_configs.hpp"
#include "daemon/cell/real_sensor.hpp"

namespace rangefit::daemon::real_sensors {
namespace {

std::vector<NamedDriver> robot_drivers(const DeviceConfig& d, const CellConfig& config,
                                       hal::Clock&) {
  std::vector<NamedDriver> out;
  if (d.protocol == JointProtocol::kPowerCube) {
    const auto c = robot_powercube_config(d, config.fusion.css.joint);
    out.push_back({d.name, std::make_unique<drivers::can::PowerCubeJointSource>(
                               c, socketcan(d.transport, drivers::can::powercube_filter(c)))});
  } else {
    const auto c = robot_joint_config(d, config.fusion.css.joint);
    out.push_back({d.name, std::make_unique<drivers::can::Cia402JointSource>(
                               c, socketcan(d.transport, drivers::can::cia402_filter(c)))});
  }
  return out;
}

}  // namespace

extern const RealSensor robot;
const RealSensor robot{"robot", robot_drivers, nullptr};

}  // namespace rangefit::daemon::real_sensors
