#pragma once
// The service's state and its diagnostics as plain values: what the pipeline reports and the
// DDS layer (daemon/dds/messages.hpp) puts on rt/rangefit/state and rt/diagnostics. Kept free
// of the generated wire types so the pipeline and the offline tools need no DDS.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rangefit::daemon {

// Lifecycle states of rt/rangefit/state (values of rangefit_msgs/State constants).
enum class LifecycleState : std::uint8_t { kStarting = 0, kIdle, kScanning, kDetecting, kFault };
const char* to_string(LifecycleState s);

struct DiagStatus {
  std::uint8_t level = 0;  // diagnostic_msgs/DiagnosticStatus: OK 0, WARN 1, ERROR 2, STALE 3
  std::string name;
  std::string message;
  std::string hardware_id;
  std::vector<std::pair<std::string, std::string>> values;
};
inline constexpr std::uint8_t kDiagOk = 0, kDiagWarn = 1, kDiagError = 2, kDiagStale = 3;

}  // namespace rangefit::daemon
