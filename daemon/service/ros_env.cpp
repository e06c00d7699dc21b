#include "daemon/service/ros_env.hpp"

#include <cstdlib>
#include <stdexcept>

namespace rangefit::daemon {

std::optional<std::uint32_t> ros_domain_id() {
  const char* text = std::getenv("ROS_DOMAIN_ID");
  if (text == nullptr || *text == '\0') return std::nullopt;
  std::uint32_t value = 0;
  for (const char* c = text; *c != '\0'; ++c) {
    if (*c < '0' || *c > '9' || value > 232) {
      throw std::invalid_argument(std::string("ROS_DOMAIN_ID: must be a whole number in 0 .. 232, "
                                              "got \"") +
                                  std::string(text).substr(0, 16) + "\"");
    }
    value = value * 10 + static_cast<std::uint32_t>(*c - '0');
  }
  if (value > 232) {
    throw std::invalid_argument("ROS_DOMAIN_ID: must be in 0 .. 232, got " + std::to_string(value));
  }
  return value;
}

}  // namespace rangefit::daemon
