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
  if (d.kind->can_nodes == nullptr) return {};
  return d.kind->can_nodes(d);
}

}  // namespace rangefit::daemon
