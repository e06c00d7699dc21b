#include "daemon/dds/ros_discovery.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

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

const dds_topic_descriptor_t* humble_discovery_descriptor() {
  static const dds_topic_descriptor_t descriptor = [] {
    const dds_topic_descriptor_t& d = rmw_dds_common_humble_msg_dds__ParticipantEntitiesInfo__desc;
    return dds_topic_descriptor_t{d.m_size,
                                  d.m_align,
                                  d.m_flagset & ~DDS_TOPIC_XTYPES_METADATA,
                                  d.m_nkeys,
                                  "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_",
                                  d.m_keys,
                                  d.m_nops,
                                  d.m_ops,
                                  d.m_meta,
                                  {nullptr, 0},
                                  {nullptr, 0},
                                  d.restrict_data_representation};
  }();
  return &descriptor;
}

namespace {

// A Gid message of either layout: the GUID, zeros after it (Humble's 8 spare bytes).
template <class GidMsg>
void fill(GidMsg& out, const Gid& gid) {
  static_assert(sizeof(out.data) >= std::tuple_size_v<Gid>);
  std::memset(out.data, 0, sizeof(out.data));
  std::memcpy(out.data, gid.data(), gid.size());
}

// The Gids of `entities`, in storage that outlives the message that points into it.
template <class GidMsg>
std::vector<GidMsg> gids(const std::vector<dds_entity_t>& entities) {
  std::vector<GidMsg> out(entities.size());
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

// Writes the participant's one node in the message layout of `writer` (Iron's or Humble's
// generated C types, which differ only in the Gid's size).
template <class Info>
bool publish_node(dds::Writer<Info>& writer, dds::Participant& participant, const RosNode& node) {
  using NodeInfo = std::remove_pointer_t<decltype(Info{}.node_entities_info_seq._buffer)>;
  using GidMsg = std::remove_pointer_t<decltype(NodeInfo{}.reader_gid_seq._buffer)>;
  std::vector<dds_entity_t> writers = node.writers;
  writers.push_back(writer.get());  // rmw_cyclonedds lists its own discovery writer too
  std::vector<GidMsg> reader_gids = gids<GidMsg>(node.readers);
  std::vector<GidMsg> writer_gids = gids<GidMsg>(writers);
  std::vector<NodeInfo> nodes(1);
  copy_bounded(nodes[0].node_namespace, node.name_space);
  copy_bounded(nodes[0].node_name, node.name);
  nodes[0].reader_gid_seq = seq_of<decltype(NodeInfo{}.reader_gid_seq)>(reader_gids);
  nodes[0].writer_gid_seq = seq_of<decltype(NodeInfo{}.writer_gid_seq)>(writer_gids);
  Info msg{};
  fill(msg.gid, gid_of(participant.get()));
  msg.node_entities_info_seq = seq_of<decltype(Info{}.node_entities_info_seq)>(nodes);
  return writer.write(msg);
}

}  // namespace

RosDiscovery::RosDiscovery(dds::Participant& participant, const RosNode& node,
                           RosGidLayout layout) {
  if (layout == RosGidLayout::kHumble) {
    humble_.emplace(participant, topics::kRosDiscovery, humble_discovery_descriptor(),
                    topics::ros_discovery_qos());
    published_ = publish_node(*humble_, participant, node);
  } else {
    iron_.emplace(participant, topics::kRosDiscovery,
                  &rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc,
                  topics::ros_discovery_qos());
    published_ = publish_node(*iron_, participant, node);
  }
}

}  // namespace rangefit::daemon
