#pragma once
// The settings a driver = "real" device's drivers run with, built from its [[devices]] table: the
// transport and the bus addresses (can_node, pan_node, tilt_node, modbus_unit; 0 = the driver's
// own default). Kept apart from RealDevices so what reaches a driver is checked without a bus,
// and so config parsing finds node clashes with the very ids the drivers will use.

#include <string>
#include <vector>

#include "daemon/config.hpp"
#include "drivers/can/cia402_joint_source.hpp"
#include "drivers/can/cia402_pan_tilt_source.hpp"
#include "drivers/can/powercube_joint_source.hpp"
#include "drivers/can/ranger_source.hpp"
#include "drivers/modbus/fhpp_axis.hpp"

namespace rangefit::daemon {

// Parses "host:port" (TCP) or "/dev/..." (RTU) into the host/port/serial fields; false when
// neither fits (*why says so).
struct ModbusAddress {
  std::string host;
  int port = 502;
  std::string serial_device;
};
bool parse_modbus_address(const std::string& transport, ModbusAddress* out, std::string* why);

// kind = "axis": the Festo drive over Modbus (unit modbus_unit); travel limits from
// axis_travel_mm. Throws std::runtime_error naming the device on a transport it cannot parse.
drivers::FhppAxisConfig fhpp_axis_config(const DeviceConfig& d, double axis_travel_mm);
// kind = "robot": the CSS's last joint (JointSample::joint = joint) on node can_node.
drivers::can::Cia402Config robot_joint_config(const DeviceConfig& d, int joint);
// kind = "robot", protocol = "powercube": the same joint as PowerCube module can_node (1).
drivers::can::PowerCubeConfig robot_powercube_config(const DeviceConfig& d, int joint);
// kind = "stripe" or "pan_tilt": the laser-stripe ranger on node can_node.
drivers::can::RangerConfig ranger_config(const DeviceConfig& d);
// kind = "pan_tilt": the head's pan and tilt axes (pan_node, tilt_node), named "<name>/angles".
drivers::can::PanTiltConfig pan_tilt_config(const DeviceConfig& d);
std::string pan_tilt_angles_name(const std::string& head);

// A CAN node id a device occupies on its interface, and the [[devices]] field that sets it.
struct CanNodeUse {
  const char* field;  // "can_node", "pan_node" or "tilt_node"
  int node;           // 1..127 as the driver will use it (defaults filled in)
  bool is_default;    // the field is not set: node is the driver's default
};
// Empty for kinds that are not on a CAN bus (css, axis).
std::vector<CanNodeUse> can_nodes(const DeviceConfig& d);

}  // namespace rangefit::daemon
