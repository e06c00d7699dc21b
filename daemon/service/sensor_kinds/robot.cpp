// kind = "robot": the robot's last joint that pivots the CSS, read over CAN (a CiA 402 node, or a
// PowerCube module with protocol = "powercube"). It moves a css sensor and takes no scan itself.
#include "daemon/service/bus_addresses.hpp"
#include "daemon/service/sensor_kind.hpp"

namespace rangefit::daemon::sensor_kinds {
namespace {

std::vector<CanNodeUse> robot_nodes(const DeviceConfig& d) {
  // PowerCube modules answer on ids of their own (0x0A0 + module), apart from CiA 402 nodes.
  if (d.protocol == JointProtocol::kPowerCube) return {};
  return {{"can_node", joint_node(d), d.can_node == 0}};
}

}  // namespace

extern const SensorKind robot;
const SensorKind robot{
    .name = "robot", .fields = {.can_node = true, .protocol = true}, .can_nodes = robot_nodes};

}  // namespace rangefit::daemon::sensor_kinds
