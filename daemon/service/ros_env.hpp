#pragma once
// ROS 2's environment as a ROS node reads it: ROS_DOMAIN_ID picks the DDS domain when nothing
// else does (rangefitd: no [dds] domain_id in the config; rangefit request|watch: no --domain),
// ROS_DISTRO the graph's message layout when the config sets no [ros] distro.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rangefit::daemon {

// The domain in ROS_DOMAIN_ID: nullopt when unset or empty; throws std::invalid_argument naming
// the variable when it is not a whole number in 0 .. 232 (the DDSI port mapping's range).
std::optional<std::uint32_t> ros_domain_id();

// Empty when distro is a ROS 2 release rangefitd speaks to (humble, iron, jazzy, kilted,
// rolling), else the reason naming them.
std::string check_ros_distro(std::string_view distro);

// ROS_DISTRO as a sourced ROS 2 shell sets it: nullopt when unset or empty; throws
// std::invalid_argument naming the variable when check_ros_distro refuses it.
std::optional<std::string> ros_distro_from_env();

// Empty when ns is a usable ROS namespace without its leading '/' ("cell1", "plant/cell_2":
// tokens of letters, digits and '_' not starting with a digit, joined by single '/', at most
// 200 characters, so every topic name stays within DDS and rmw limits), else the reason.
std::string check_ros_namespace(std::string_view ns);

// Empty when p is a usable DDS partition name (1..128 printable ASCII characters without the
// wildcards * ? [ ] \ that Cyclone would match as a pattern), else the reason.
std::string check_partition(std::string_view p);

}  // namespace rangefit::daemon
