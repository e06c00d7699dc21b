#include "drivers/modbus/position_check.hpp"

#include <cmath>
#include <cstdio>

namespace rangefit::drivers {

std::string check_position(const PositionCheckConfig& config, double position_mm,
                           hal::Timestamp stamp, const std::optional<PositionReference>& previous) {
  char buf[200];
  if (!std::isfinite(position_mm) || position_mm < config.min_mm - config.margin_mm ||
      position_mm > config.max_mm + config.margin_mm) {
    std::snprintf(buf, sizeof buf,
                  "implausible position %.3f mm outside travel [%.1f, %.1f] mm: check byte order "
                  "and increments per mm",
                  position_mm, config.min_mm, config.max_mm);
    return buf;
  }
  if (!previous) return {};
  const double dt_s = std::chrono::duration<double>(stamp - previous->stamp).count();
  const double jump = std::abs(position_mm - previous->position_mm);
  // Twice the top speed plus the margin: timing jitter never gets near it, a byte swap does.
  const double limit = 2.0 * config.max_speed_mm_s * std::max(dt_s, 0.0) + config.margin_mm;
  if (jump > limit) {
    std::snprintf(buf, sizeof buf,
                  "implausible position jump of %.3f mm in %.1f ms (limit %.3f mm): check byte "
                  "order and increments per mm",
                  jump, dt_s * 1e3, limit);
    return buf;
  }
  return {};
}

}  // namespace rangefit::drivers
