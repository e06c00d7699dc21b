#include "daemon/dds/dds.hpp"

namespace rangefit::dds {

Qos::Qos(const QosSpec& spec) : qos_(dds_create_qos()) {
  dds_qset_reliability(qos_, spec.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_SECS(1));
  dds_qset_durability(
      qos_, spec.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  if (spec.keep_all) {
    dds_qset_history(qos_, DDS_HISTORY_KEEP_ALL, DDS_LENGTH_UNLIMITED);
    dds_qset_resource_limits(qos_, spec.max_samples, DDS_LENGTH_UNLIMITED, spec.max_samples);
  } else {
    dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, spec.depth);
  }
  if (spec.transient_local) {
    // What a late-joining reader gets: the last `depth` samples, also for keep-all writers.
    dds_qset_durability_service(qos_, 0, DDS_HISTORY_KEEP_LAST, spec.depth, DDS_LENGTH_UNLIMITED,
                                DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  }
  // ROS 2 (rmw_cyclonedds_cpp) only speaks XCDR1; pin it so a newer default cannot change it.
  dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos_, 1, &xcdr1);
}

Participant::Participant(dds_domainid_t domain, const std::string& config,
                         const std::string& partition) {
  if (!config.empty()) {
    const dds_entity_t d = dds_create_domain(domain, config.c_str());
    if (d < 0) throw DdsError("create domain " + std::to_string(domain) + " with its config", d);
    domain_ = Entity(d);
  }
  const dds_entity_t p = dds_create_participant(domain, nullptr, nullptr);
  if (p < 0) throw DdsError("create participant on domain " + std::to_string(domain), p);
  entity_ = Entity(p);
  if (!partition.empty()) {
    dds_qos_t* q = dds_create_qos();
    dds_qset_partition1(q, partition.c_str());
    const dds_entity_t pub = dds_create_publisher(p, q, nullptr);
    const dds_entity_t sub = dds_create_subscriber(p, q, nullptr);
    dds_delete_qos(q);
    if (pub < 0) throw DdsError("create publisher in partition " + partition, pub);
    if (sub < 0) throw DdsError("create subscriber in partition " + partition, sub);
    publisher_ = Entity(pub);
    subscriber_ = Entity(sub);
  }
}

dds_entity_t Participant::topic(const char* name, const dds_topic_descriptor_t* desc,
                                const QosSpec& qos) {
  // Topic QoS only matters for defaults; readers and writers carry their own. Cyclone returns
  // the same underlying topic for repeated creation, and deletes it with the participant.
  const Qos q(qos);
  const dds_entity_t t = dds_create_topic(entity_.get(), desc, name, q.get(), nullptr);
  if (t < 0) throw DdsError(std::string("create topic ") + name, t);
  return t;
}

}  // namespace rangefit::dds
