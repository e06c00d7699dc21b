#include "daemon/service/sensor_kind.hpp"

#include <stdexcept>

namespace rangefit::daemon {
namespace {

const SensorKind kNone{};

}  // namespace

const SensorKind* find_sensor_kind(std::string_view name) {
  for (const SensorKind* k : all_sensor_kinds()) {
    if (name == k->name || (*k->cli_name != '\0' && name == k->cli_name)) return k;
  }
  return nullptr;
}

std::string sensor_kind_names(const std::function<bool(const SensorKind&)>& keep,
                              const char* last) {
  std::vector<const char*> names;
  for (const SensorKind* k : all_sensor_kinds()) {
    if (!keep || keep(*k)) names.push_back(k->name);
  }
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? last : ", ";
    out += names[i];
  }
  return out;
}

DeviceKind::DeviceKind() : kind_(&kNone) {}

DeviceKind::DeviceKind(std::string_view name) : kind_(find_sensor_kind(name)) {
  if (kind_ == nullptr) {
    throw std::invalid_argument("unknown device kind \"" + std::string(name) + "\" (one of " +
                                sensor_kind_names() + ")");
  }
}

}  // namespace rangefit::daemon
