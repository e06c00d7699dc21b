#pragma once
// Plausibility of a decoded axis position: a wrong byte order or increments-per-mm gives positions
// outside the travel or jumps no drive can make, which must never reach fusion as valid samples.

#include <optional>
#include <string>

#include "hal/time.hpp"

namespace rangefit::drivers {

struct PositionCheckConfig {
  double min_mm = 0.0;  // travel, mm
  double max_mm = 1000.0;
  double margin_mm = 5.0;         // tolerated overshoot beyond the travel, mm
  double max_speed_mm_s = 500.0;  // fastest the drive can move, mm/s
};

struct PositionReference {
  double position_mm = 0.0;
  hal::Timestamp stamp{};
};

// Empty when plausible, else the reason ("... check byte order and increments per mm").
std::string check_position(const PositionCheckConfig& config, double position_mm,
                           hal::Timestamp stamp, const std::optional<PositionReference>& previous);

}  // namespace rangefit::drivers
