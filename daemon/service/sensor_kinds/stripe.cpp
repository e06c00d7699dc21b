// kind = "stripe": the laser-stripe ranger over the linear axis of the stripe cell (thesis
// ch. 5). A linear sweep, in mm; the ranger is CAN node can_node. The service calibrates it from
// the hollow cube on the cell's table (calibrate target "stripe"). Its drivers and scans:
// daemon/cell/sensors/stripe.cpp and sim/stripe.cpp.
#include "daemon/service/bus_addresses.hpp"
#include "daemon/service/sensor_kind.hpp"

namespace rangefit::daemon::sensor_kinds {
namespace {

std::vector<CanNodeUse> stripe_nodes(const DeviceConfig& d) {
  return {{"can_node", ranger_node(d), d.can_node == 0}};
}

}  // namespace

extern const SensorKind stripe;
const SensorKind stripe{.name = "stripe",
                        .scans = true,
                        .sweep_linear = true,
                        .moved_by = "axis",
                        .calibrated_by_service = true,
                        .fields = {.can_node = true},
                        .can_nodes = stripe_nodes};

}  // namespace rangefit::daemon::sensor_kinds
