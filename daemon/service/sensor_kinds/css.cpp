// kind = "css": the Conical Scanning Sensor on the robot's last joint (thesis ch. 4). It scans
// while the robot program pivots that joint through -delta .. +delta: a rotary sweep, in rad.
// On USB, so no bus address. The service calibrates its mount on the joint from a precision
// sphere scanned at several robot poses (calibrate target "css"). Its drivers and scans:
// daemon/cell/sensors/css.cpp and sim/css.cpp.
#include "daemon/service/sensor_kind.hpp"

namespace rangefit::daemon::sensor_kinds {

extern const SensorKind css;
const SensorKind css{
    .name = "css", .scans = true, .moved_by = "robot", .calibrated_by_service = true};

}  // namespace rangefit::daemon::sensor_kinds
