// kind = "axis": the stripe cell's linear axis (a Festo drive over Modbus, unit modbus_unit). It
// moves a stripe sensor and takes no scan itself; its sweep is linear, in mm.
#include "daemon/service/sensor_kind.hpp"

namespace rangefit::daemon::sensor_kinds {

extern const SensorKind axis;
const SensorKind axis{.name = "axis", .sweep_linear = true, .fields = {.modbus_unit = true}};

}  // namespace rangefit::daemon::sensor_kinds
