#pragma once
// rangefit_msgs/Models: the object models a running rangefitd knows, for `rangefit models` and
// any ROS 2 node that wants to offer them. Built from the configuration; owns its storage.

#include <string>
#include <vector>

#include "daemon/service/config.hpp"
#include "rangefit_msgs.h"

namespace rangefit::daemon {

struct ModelInfo {
  std::string name;
  std::vector<std::string> parts;
};

class ModelsOut {
 public:
  ModelsOut(const DaemonConfig& config, std::string frame);
  ModelsOut(const ModelsOut&) = delete;
  ModelsOut& operator=(const ModelsOut&) = delete;
  const rangefit_msgs_msg_dds__Models_& msg() const { return msg_; }

 private:
  std::string frame_;
  std::vector<std::string> names_, parts_;
  std::vector<char*> name_ptrs_, part_ptrs_;
  std::vector<std::uint32_t> counts_;
  rangefit_msgs_msg_dds__Models_ msg_{};
};

// Decodes a Models message; a part count that runs past the part names ends the list there.
std::vector<ModelInfo> from_msg(const rangefit_msgs_msg_dds__Models_& msg);

}  // namespace rangefit::daemon
