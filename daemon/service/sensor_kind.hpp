#pragma once
// The kinds of device a [[devices]] table names (kind = "css", ...): what the configuration, the
// requests and the interfaces need to know of each. Every kind is one file of
// daemon/service/sensor_kinds/ that registers itself (docs/adding_a_sensor.md); its drivers and
// scans are its files of daemon/cell/sensors/. The kind is read once, at config load, into a
// DeviceKind; nothing else looks at its name.

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rangefit::daemon {

struct DeviceConfig;
struct CanNodeUse;

// The [[devices]] fields a kind reads besides the common ones (name, driver, transport, sweep...).
struct KindFields {
  bool can_node = false;     // a CANopen node (or PowerCube module) id
  bool pan_node = false;     // the pan axis' CiA 402 node
  bool tilt_node = false;    // the tilt axis' CiA 402 node
  bool modbus_unit = false;  // a Modbus unit id
  bool protocol = false;     // protocol = "cia402" | "powercube"
};

struct SensorKind {
  const char* name = "";      // kind = "<name>" in [[devices]]
  const char* cli_name = "";  // its spelling in `rangefit simulate --sensor`; "": name
  bool scans = false;         // takes scans (requests name it); else it moves a sensor
  bool sweep_linear = false;  // sweeps along an axis, mm (metres on the wire); else rad
  const char* moved_by = "";  // the kind of device that moves it in the real cell; "": itself
  // A calibrate request's target of this name is the body the service calibrates it from.
  bool calibrated_by_service = false;
  KindFields fields{};
  // The CAN node ids a driver = "real" device of this kind occupies; null: none.
  std::vector<CanNodeUse> (*can_nodes)(const DeviceConfig& d) = nullptr;
};

// Every registered kind, in name order (generated from the files of daemon/service/sensor_kinds).
std::span<const SensorKind* const> all_sensor_kinds();
// The kind of that name (or CLI spelling); null when no kind has it.
const SensorKind* find_sensor_kind(std::string_view name);
// The names of the kinds `keep` holds for (empty: all), "a, b or c" ("a, b, c" with last = ", ").
std::string sensor_kind_names(const std::function<bool(const SensorKind&)>& keep = {},
                              const char* last = " or ");

// DeviceConfig::kind: one of the registered kinds (or none, a device not yet read). Compared as
// a kind, never by its name.
class DeviceKind {
 public:
  DeviceKind();  // none: no fields, does not scan
  DeviceKind(const SensorKind& kind) : kind_(&kind) {}
  // The registered kind of that name; throws std::invalid_argument when there is none.
  DeviceKind(std::string_view name);
  DeviceKind(const char* name) : DeviceKind(std::string_view(name)) {}
  DeviceKind(const std::string& name) : DeviceKind(std::string_view(name)) {}

  const SensorKind& operator*() const { return *kind_; }
  const SensorKind* operator->() const { return kind_; }
  std::string_view name() const { return kind_->name; }
  operator std::string_view() const { return name(); }  // for messages and logs

  bool operator==(const DeviceKind& o) const { return kind_ == o.kind_; }
  bool operator==(const char*) const = delete;  // a kind is compared as a kind
  bool operator==(std::string_view) const = delete;

 private:
  const SensorKind* kind_;
};

}  // namespace rangefit::daemon
