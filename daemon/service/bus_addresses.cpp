#include "daemon/service/bus_addresses.hpp"

namespace rangefit::daemon {
namespace {

int or_default(int configured, int fallback) { return configured != 0 ? configured : fallback; }

}  // namespace

int joint_node(const DeviceConfig& d) { return or_default(d.can_node, kDefaultJointNode); }
int ranger_node(const DeviceConfig& d) { return or_default(d.can_node, kDefaultRangerNode); }
int pan_node(const DeviceConfig& d) { return or_default(d.pan_node, kDefaultPanNode); }
int tilt_node(const DeviceConfig& d) { return or_default(d.tilt_node, kDefaultTiltNode); }

std::vector<CanNodeUse> can_nodes(const DeviceConfig& d) {
  const CanNodeUse ranger{"can_node", ranger_node(d), d.can_node == 0};
  if (d.kind == "robot") {
    // PowerCube modules answer on ids of their own (0x0A0 + module), apart from CiA 402 nodes.
    if (d.protocol == JointProtocol::kPowerCube) return {};
    return {{"can_node", joint_node(d), d.can_node == 0}};
  }
  if (d.kind == "stripe") return {ranger};
  if (d.kind == "pan_tilt") {
    return {ranger,
            {"pan_node", pan_node(d), d.pan_node == 0},
            {"tilt_node", tilt_node(d), d.tilt_node == 0}};
  }
  return {};
}

}  // namespace rangefit::daemon
