// kind = "pan_tilt": the laser-stripe ranger on a pan-tilt head (thesis 5.3). It scans while the
// cell program pans the head: a rotary sweep, in rad. The ranger (can_node) and the head's pan
// and tilt axes (pan_node, tilt_node) share one CAN interface. `rangefit simulate` spells it
// "pantilt". The service calibrates it from the hollow cube swept at several tilts (calibrate
// target "pantilt"). A further camera of the head's laser plane ([[fusion.pan_tilt.cameras]]) is
// a pan_tilt device whose `motion` names the head: it has only its ranger (can_node). Its drivers
// and scans: daemon/cell/sensors/pan_tilt.cpp and sim/pan_tilt.cpp.
#include "daemon/service/bus_addresses.hpp"
#include "daemon/service/sensor_kind.hpp"

namespace rangefit::daemon::sensor_kinds {
namespace {

std::vector<CanNodeUse> pan_tilt_nodes(const DeviceConfig& d) {
  if (!d.motion.empty()) return {{"can_node", ranger_node(d), d.can_node == 0}};
  return {{"can_node", ranger_node(d), d.can_node == 0},
          {"pan_node", pan_node(d), d.pan_node == 0},
          {"tilt_node", tilt_node(d), d.tilt_node == 0}};
}

}  // namespace

extern const SensorKind pan_tilt;
const SensorKind pan_tilt{.name = "pan_tilt",
                          .cli_name = "pantilt",
                          .scans = true,
                          .calibrated_by_service = true,
                          .fields = {.can_node = true, .pan_node = true, .tilt_node = true},
                          .can_nodes = pan_tilt_nodes};

}  // namespace rangefit::daemon::sensor_kinds
