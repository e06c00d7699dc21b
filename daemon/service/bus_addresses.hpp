#pragma once
// The CAN node ids a driver = "real" device occupies, as its [[devices]] table sets them or as
// the drivers default them. Config parsing checks node clashes with these ids, and the drivers'
// settings (daemon/cell/driver_configs.hpp) are built from them, so both always agree without the
// configuration depending on the drivers.

#include <vector>

#include "daemon/service/config.hpp"

namespace rangefit::daemon {

// The drivers' defaults (0 in the table): the CSS robot joint's CiA 402 node, the laser-stripe
// ranger's node, the pan-tilt head's pan and tilt nodes.
inline constexpr int kDefaultJointNode = 1;
inline constexpr int kDefaultRangerNode = 0x20;
inline constexpr int kDefaultPanNode = 1;
inline constexpr int kDefaultTiltNode = 2;

// can_node (robot: its joint; stripe, pan_tilt: the ranger), pan_node, tilt_node with the
// defaults filled in.
int joint_node(const DeviceConfig& d);
int ranger_node(const DeviceConfig& d);
int pan_node(const DeviceConfig& d);
int tilt_node(const DeviceConfig& d);

// A CAN node id a device occupies on its interface, and the [[devices]] field that sets it.
struct CanNodeUse {
  const char* field;  // "can_node", "pan_node" or "tilt_node"
  int node;           // 1..127 as the driver will use it (defaults filled in)
  bool is_default;    // the field is not set: node is the driver's default
};
// As the device's kind declares them (SensorKind::can_nodes): none for kinds that are not on a
// CAN bus (css, axis) and for PowerCube modules.
std::vector<CanNodeUse> can_nodes(const DeviceConfig& d);

}  // namespace rangefit::daemon
