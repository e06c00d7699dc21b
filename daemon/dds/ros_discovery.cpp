#include "daemon/dds/ros_discovery.hpp"

#include <algorithm>
#include <cstring>

namespace rangefit::daemon {

namespace topics {
dds::QosSpec ros_discovery_qos() {
  dds::QosSpec q;
  q.reliable = true;
  q.transient_local = true;
  q.depth = 1;
  return q;
}
}  // namespace topics

Gid gid_of(dds_entity_t entity) {
  Gid gid{};
  dds_guid_t guid;
  static_assert(sizeof(guid.v) == std::tuple_size_v<Gid>);
  if (dds_get_guid(entity, &guid) == DDS_RETCODE_OK) std::memcpy(gid.data(), guid.v, gid.size());
  return gid;
}

std::string ros_node_namespace(const std::string& ros_namespace) {
  return "/" + ros_namespace;
}

namespace {

void fill(rmw_dds_common_msg_dds__Gid_& out, const Gid& gid) {
  std::memcpy(out.data, gid.data(), gid.size());
}

// The Gids of `entities`, in storage that outlives the message that points into it.
std::vector<rmw_dds_common_msg_dds__Gid_> gids(const std::vector<dds_entity_t>& entities) {
  std::vector<rmw_dds_common_msg_dds__Gid_> out(entities.size());
  for (std::size_t i = 0; i < entities.size(); ++i) fill(out[i], gid_of(entities[i]));
  return out;
}

// string<256> is a char[257] in the generated C (zeroed: the copy stays terminated).
template <std::size_t N>
void copy_bounded(char (&out)[N], const std::string& text) {
  std::memset(out, 0, N);
  std::memcpy(out, text.data(), std::min(text.size(), N - 1));
}

template <class Seq, class T>
Seq seq_of(std::vector<T>& v) {
  Seq s{};
  s._length = s._maximum = static_cast<std::uint32_t>(v.size());
  s._buffer = v.empty() ? nullptr : v.data();
  s._release = false;
  return s;
}

}  // namespace

RosDiscovery::RosDiscovery(dds::Participant& participant, const RosNode& node)
    : writer_(participant, topics::kRosDiscovery,
              &rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc,
              topics::ros_discovery_qos()) {
  std::vector<dds_entity_t> writers = node.writers;
  writers.push_back(writer_.get());  // rmw_cyclonedds lists its own discovery writer too
  std::vector<rmw_dds_common_msg_dds__Gid_> reader_gids = gids(node.readers);
  std::vector<rmw_dds_common_msg_dds__Gid_> writer_gids = gids(writers);
  std::vector<rmw_dds_common_msg_dds__NodeEntitiesInfo_> nodes(1);
  copy_bounded(nodes[0].node_namespace, node.name_space);
  copy_bounded(nodes[0].node_name, node.name);
  nodes[0].reader_gid_seq =
      seq_of<dds_sequence_rmw_dds_common_msg_dds__Gid_>(reader_gids);
  nodes[0].writer_gid_seq =
      seq_of<dds_sequence_rmw_dds_common_msg_dds__Gid_>(writer_gids);
  rmw_dds_common_msg_dds__ParticipantEntitiesInfo_ msg{};
  fill(msg.gid, gid_of(participant.get()));
  msg.node_entities_info_seq =
      seq_of<dds_sequence_rmw_dds_common_msg_dds__NodeEntitiesInfo_>(nodes);
  published_ = writer_.write(msg);
}

}  // namespace rangefit::daemon
