#include "daemon/cell/driver_configs.hpp"

#include <cstdlib>
#include <stdexcept>

namespace rangefit::daemon {
namespace {

template <class T>
void set_if(int configured, T& field) {
  if (configured != 0) field = static_cast<T>(configured);
}

}  // namespace

bool parse_modbus_address(const std::string& transport, ModbusAddress* out, std::string* why) {
  if (transport.rfind("/dev/", 0) == 0) {
    out->serial_device = transport;
    return true;
  }
  const auto colon = transport.rfind(':');
  if (colon == std::string::npos || colon == 0) {
    *why = "must be \"host:port\" (Modbus TCP) or \"/dev/...\" (RTU), got \"" + transport + "\"";
    return false;
  }
  char* end = nullptr;
  const long port = std::strtol(transport.c_str() + colon + 1, &end, 10);
  if (end == transport.c_str() + colon + 1 || *end != '\0' || port < 1 || port > 65535) {
    *why = "port of \"" + transport + "\" must be 1..65535";
    return false;
  }
  out->host = transport.substr(0, colon);
  out->port = static_cast<int>(port);
  return true;
}

drivers::FhppAxisConfig fhpp_axis_config(const DeviceConfig& d, double axis_travel_mm) {
  ModbusAddress a;
  std::string why;
  if (!parse_modbus_address(d.transport, &a, &why)) {
    throw std::runtime_error("device " + d.name + ": transport: " + why);
  }
  drivers::FhppAxisConfig c;
  c.name = d.name;
  c.link.host = a.host;
  c.link.port = a.port;
  c.link.serial_device = a.serial_device;
  set_if(d.modbus_unit, c.link.unit_id);
  c.travel.max_mm = axis_travel_mm;
  return c;
}

drivers::can::Cia402Config robot_joint_config(const DeviceConfig& d, int joint) {
  drivers::can::Cia402Config c;
  c.name = d.name;
  drivers::can::Cia402JointConfig j;
  j.joint = static_cast<std::uint8_t>(joint);
  j.node = static_cast<std::uint8_t>(joint_node(d));
  c.joints.push_back(j);
  return c;
}

drivers::can::PowerCubeConfig robot_powercube_config(const DeviceConfig& d, int joint) {
  drivers::can::PowerCubeConfig c;
  c.name = d.name;
  drivers::can::PowerCubeModuleConfig m;
  m.joint = static_cast<std::uint8_t>(joint);
  set_if(d.can_node, m.module);
  c.modules.push_back(m);
  return c;
}

drivers::can::RangerConfig ranger_config(const DeviceConfig& d, const hal::StripeRanger& geometry) {
  drivers::can::RangerConfig c;
  c.name = d.name;
  c.node = static_cast<std::uint8_t>(ranger_node(d));
  c.fan_angle_rad = geometry.fan_angle_rad;
  return c;
}

drivers::can::PanTiltConfig pan_tilt_config(const DeviceConfig& d) {
  drivers::can::PanTiltConfig c;
  c.bus.name = pan_tilt_angles_name(d.name);
  c.pan.node = static_cast<std::uint8_t>(pan_node(d));
  c.tilt.node = static_cast<std::uint8_t>(tilt_node(d));
  return c;
}

std::string pan_tilt_angles_name(const std::string& head) { return head + "/angles"; }

}  // namespace rangefit::daemon
