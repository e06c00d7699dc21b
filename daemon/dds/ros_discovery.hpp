#pragma once
// rangefitd as a node of the ROS 2 graph: what rmw_cyclonedds publishes for each of its
// participants on ros_discovery_info (rmw_dds_common/msg/ParticipantEntitiesInfo; no rt/ prefix;
// reliable, transient-local, depth 1), so that `ros2 node list` shows /rangefitd (or
// /<namespace>/rangefitd) and `ros2 node info` gives it its topics and its service. A Gid is the
// DDS GUID of the participant, reader or writer: 16 bytes from Iron on, 24 (the GUID and 8 zero
// bytes) in Humble, whose graph reads only its own layout under the same type name.

#include <dds/dds.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "daemon/dds/dds.hpp"
#include "rmw_dds_common.h"
#include "rmw_dds_common_humble.h"

namespace rangefit::daemon {

namespace topics {
inline constexpr const char* kRosDiscovery = "ros_discovery_info";
dds::QosSpec ros_discovery_qos();  // reliable, transient-local, depth 1
}  // namespace topics

using Gid = std::array<std::uint8_t, 16>;

// The GUID of a DDS entity (participant, reader, writer); all zeros when it has none.
Gid gid_of(dds_entity_t entity);

struct RosNode {
  std::string name;       // "rangefitd"
  std::string name_space; // "/" or "/cell1"
  std::vector<dds_entity_t> readers, writers;
};

// Which ROS 2 graph reads ros_discovery_info: Humble's 24-byte Gid or the 16 bytes of Iron on.
enum class RosGidLayout { kIronOrLater, kHumble };

// Humble's ParticipantEntitiesInfo under the DDS type name both layouts share (without XTypes
// type information: Humble's rmw_cyclonedds matches by name).
const dds_topic_descriptor_t* humble_discovery_descriptor();

// The ROS node name space of a rangefit ROS namespace ("" -> "/", "cell1" -> "/cell1").
std::string ros_node_namespace(const std::string& ros_namespace);

// Publishes the participant's one node once (transient-local: late graph readers get it too).
// Throws dds::DdsError when the writer cannot be created (start-up only).
class RosDiscovery {
 public:
  RosDiscovery(dds::Participant& participant, const RosNode& node,
               RosGidLayout layout = RosGidLayout::kIronOrLater);
  bool published() const { return published_; }

 private:
  using Iron = rmw_dds_common_msg_dds__ParticipantEntitiesInfo_;
  using Humble = rmw_dds_common_humble_msg_dds__ParticipantEntitiesInfo_;
  std::optional<dds::Writer<Iron>> iron_;
  std::optional<dds::Writer<Humble>> humble_;
  bool published_ = false;
};

}  // namespace rangefit::daemon
