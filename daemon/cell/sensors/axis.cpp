// kind = "axis", driver = "real": the stripe cell's linear axis, drivers::FhppAxis (Festo FHPP
// over Modbus): "host:port" (TCP) or "/dev/tty..." (RTU), unit modbus_unit (default 1), travel
// limits from the stripe cell's geometry. It moves a stripe sensor and takes no scan itself.
#include "daemon/cell/driver_configs.hpp"
#include "daemon/cell/real_sensor.hpp"

namespace rangefit::daemon::real_sensors {
namespace {

std::vector<NamedDriver> axis_drivers(const DeviceConfig& d, const CellConfig& config,
                                      hal::Clock&) {
  std::vector<NamedDriver> out;
  out.push_back({d.name, std::make_unique<drivers::FhppAxis>(fhpp_axis_config(
                             d, config.fusion.stripe_cell.geometry.axis_travel_mm))});
  return out;
}

}  // namespace

extern const RealSensor axis;
const RealSensor axis{"axis", axis_drivers, nullptr};

}  // namespace rangefit::daemon::real_sensors
