#pragma once
// The settings a driver = "real" device's drivers run with, built from its [[devices]] table: the
// transport and the bus addresses (can_node, pan_node, tilt_node, modbus_unit; 0 = the driver's
// own default, daemon/service/bus_addresses.hpp). Kept apart from RealDevices so what reaches a
// driver is checked without a bus.

#include <string>
#include <vector>

#include "daemon/service/bus_addresses.hpp"
#include "daemon/service/config.hpp"
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
// kind = "stripe" or "pan_tilt": the laser-stripe ranger on node can_node, its columns on the fan
// rays of `geometry` (the cell's or the head's ranger, as fusion reads the points back).
drivers::can::RangerConfig ranger_config(const DeviceConfig& d, const hal::StripeRanger& geometry);
// kind = "pan_tilt": the head's pan and tilt axes (pan_node, tilt_node), named "<name>/angles".
drivers::can::PanTiltConfig pan_tilt_config(const DeviceConfig& d);
std::string pan_tilt_angles_name(const std::string& head);

}  // namespace rangefit::daemon
