#pragma once
// Angles are radians inside; options and messages that speak degrees convert with this.

#include <numbers>

namespace rangefit {

inline constexpr double kDeg = std::numbers::pi / 180.0;  // one degree, in radians

}  // namespace rangefit
