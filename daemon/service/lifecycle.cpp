#include "daemon/service/lifecycle.hpp"

namespace rangefit::daemon {

const char* to_string(LifecycleState s) {
  switch (s) {
    case LifecycleState::kStarting:
      return "starting";
    case LifecycleState::kIdle:
      return "idle";
    case LifecycleState::kScanning:
      return "scanning";
    case LifecycleState::kDetecting:
      return "detecting";
    case LifecycleState::kFault:
      return "fault";
  }
  return "?";
}

}  // namespace rangefit::daemon
