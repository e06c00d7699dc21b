#pragma once
// ROS 2's environment as a ROS node reads it: ROS_DOMAIN_ID picks the DDS domain when nothing
// else does (rangefitd: no [dds] domain_id in the config; rangefit request|watch: no --domain).

#include <cstdint>
#include <optional>
#include <string>

namespace rangefit::daemon {

// The domain in ROS_DOMAIN_ID: nullopt when unset or empty; throws std::invalid_argument naming
// the variable when it is not a whole number in 0 .. 232 (the DDSI port mapping's range).
std::optional<std::uint32_t> ros_domain_id();

}  // namespace rangefit::daemon
