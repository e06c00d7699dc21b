#pragma once
// Frame ids rangefitd puts in its messages' headers and on /tf ([frames] in the config): the
// frame the fused clouds and poses are in (REP 105 calls the cell's fixed frame "world" or
// "base_link"), and one frame per sensor for its mount on /tf_static. Every id is checked like
// tf2 checks them: no leading '/'; letters, digits and _ - . /

#include <map>
#include <string>
#include <string_view>

namespace rangefit::daemon {

struct FramesConfig {
  std::string world = "world";                 // [frames] world = "base_link"
  std::map<std::string, std::string> sensors;  // [frames] <device name> = "<frame id>"

  // The sensor's frame id: the configured one, else the device's name.
  std::string sensor(const std::string& device) const {
    const auto it = sensors.find(device);
    return it == sensors.end() ? device : it->second;
  }
  bool operator==(const FramesConfig&) const = default;
};

// Empty when id is a usable frame id (1..128 characters of [A-Za-z0-9_./-], not starting with
// '/'), else the reason.
inline std::string check_frame_id(std::string_view id) {
  if (id.empty()) return "must not be empty";
  if (id.size() > 128) return "longer than 128 characters";
  if (id.front() == '/') return "must not start with '/' (tf2 frame ids are relative)";
  for (char c : id) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '/' || c == '.' || c == '-';
    if (!ok) return "may hold only letters, digits, '_', '-', '.' and '/'";
  }
  return "";
}

}  // namespace rangefit::daemon
