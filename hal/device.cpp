#include "hal/device.hpp"

namespace rangefit::hal {

const char* to_string(DeviceState s) {
  switch (s) {
    case DeviceState::kDisconnected: return "disconnected";
    case DeviceState::kConnecting: return "connecting";
    case DeviceState::kReady: return "ready";
    case DeviceState::kStreaming: return "streaming";
    case DeviceState::kFault: return "fault";
  }
  return "unknown";
}

}  // namespace rangefit::hal
