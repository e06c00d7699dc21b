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

std::string check_ros_distro(std::string_view distro) {
  for (std::string_view known : {"humble", "iron", "jazzy", "kilted", "rolling"}) {
    if (distro == known) return "";
  }
  return "must be one of humble, iron, jazzy, kilted, rolling";
}

std::optional<std::string> ros_distro_from_env() {
  const char* text = std::getenv("ROS_DISTRO");
  if (text == nullptr || *text == '\0') return std::nullopt;
  const std::string distro(text);
  if (auto why = check_ros_distro(distro); !why.empty()) {
    throw std::invalid_argument("ROS_DISTRO: " + why + ", got \"" + distro.substr(0, 16) + "\"");
  }
  return distro;
}

std::string check_ros_namespace(std::string_view ns) {
  if (ns.empty()) return "must not be empty";
  if (ns.size() > 200) return "longer than 200 characters";
  bool token_start = true;
  for (char c : ns) {
    const bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    const bool digit = c >= '0' && c <= '9';
    if (c == '/') {
      if (token_start) return "has an empty token (a leading, trailing or double '/')";
      token_start = true;
    } else if (alpha || (digit && !token_start)) {
      token_start = false;
    } else if (digit) {
      return "has a token that starts with a digit";
    } else {
      return "may hold only letters, digits, '_' and '/'";
    }
  }
  if (token_start) return "has an empty token (a leading, trailing or double '/')";
  return "";
}

std::string check_partition(std::string_view p) {
  if (p.empty()) return "must not be empty";
  if (p.size() > 128) return "longer than 128 characters";
  for (char c : p) {
    if (c < 0x21 || c > 0x7e) return "may hold only printable ASCII characters without spaces";
    if (c == '*' || c == '?' || c == '[' || c == ']' || c == '\\') {
      return "must not hold the wildcards * ? [ ] \\";
    }
  }
  return "";
}

}  // namespace rangefit::daemon
