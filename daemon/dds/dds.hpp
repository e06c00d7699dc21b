#pragma once
// A small RAII layer over the Cyclone DDS C API. Entities are deleted in the destructor; writers
// and readers are typed by the idlc-generated C struct and its topic descriptor. QoS is spelled
// as a QosSpec so that each topic's contract reads in one line at the call site.
// Everything is written as XCDR1, as ROS 2 (rmw_cyclonedds) expects.

#include <dds/dds.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rangefit::dds {

struct QosSpec {
  bool reliable = true;
  bool transient_local = false;
  int depth = 1;  // keep-last history depth
  // Keep-all history bounded by max_samples (resource limits): a reliable writer keeps every
  // unacknowledged sample (Cyclone drops unacknowledged ones beyond a keep-last depth) and a full
  // reader makes the writer resend instead of losing a sample. Transient-local topics still
  // replay only the last `depth` samples to late joiners (durability service history).
  bool keep_all = false;
  int max_samples = 256;
};

// One topic as both sides open it: name, wire type (the idlc descriptor of T) and QoS.
template <class T>
struct Topic {
  std::string name;
  const dds_topic_descriptor_t* type;
  QosSpec qos;
};

class DdsError : public std::runtime_error {
 public:
  DdsError(const std::string& what, dds_return_t rc)
      : std::runtime_error(what + ": " + dds_strretcode(rc)) {}
};

// Owns one dds_entity_t; deleting it deletes its children (topics, readers, writers).
class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  Entity(Entity&& o) noexcept : handle_(std::exchange(o.handle_, 0)) {}
  Entity& operator=(Entity&& o) noexcept {
    if (this != &o) {
      reset();
      handle_ = std::exchange(o.handle_, 0);
    }
    return *this;
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  ~Entity() { reset(); }

  dds_entity_t get() const { return handle_; }
  void reset() {
    if (handle_ > 0) dds_delete(handle_);
    handle_ = 0;
  }

 private:
  dds_entity_t handle_ = 0;
};

class Qos {
 public:
  explicit Qos(const QosSpec& spec);
  ~Qos() { dds_delete_qos(qos_); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  const dds_qos_t* get() const { return qos_; }

 private:
  dds_qos_t* qos_;
};

class Participant {
 public:
  // Throws DdsError when the domain cannot be joined (bad config, no network): start-up only.
  // config (Cyclone's configuration: file URIs and XML fragments, CYCLONEDDS_URI syntax), when
  // not empty, creates the domain with it for this participant alone instead of the process'
  // default configuration. partition, when not empty, is the one DDS partition every writer and
  // reader of the participant is in: they match only entities of the same partition.
  explicit Participant(dds_domainid_t domain, const std::string& config = {},
                       const std::string& partition = {});
  dds_entity_t get() const { return entity_.get(); }
  dds_entity_t topic(const char* name, const dds_topic_descriptor_t* desc, const QosSpec& qos);
  // The parents of writers and readers: the partition's publisher and subscriber, else the
  // participant itself (Cyclone then makes implicit ones in the default partition).
  dds_entity_t publisher() const { return publisher_.get() > 0 ? publisher_.get() : get(); }
  dds_entity_t subscriber() const { return subscriber_.get() > 0 ? subscriber_.get() : get(); }

 private:
  Entity domain_;  // only when created with a config of its own
  Entity entity_;
  Entity publisher_, subscriber_;  // only with a partition
};

// T is the idlc-generated C struct whose descriptor is passed in.
template <class T>
class Writer {
 public:
  Writer(Participant& p, const char* topic, const dds_topic_descriptor_t* desc,
         const QosSpec& qos) {
    const Qos q(qos);
    const dds_entity_t w =
        dds_create_writer(p.publisher(), p.topic(topic, desc, qos), q.get(), nullptr);
    if (w < 0) throw DdsError(std::string("create writer ") + topic, w);
    entity_ = Entity(w);
  }
  Writer(Participant& p, const Topic<T>& t) : Writer(p, t.name.c_str(), t.type, t.qos) {}
  // Returns false when the sample could not be written (never throws: cyclic path).
  bool write(const T& sample) { return dds_write(entity_.get(), &sample) >= 0; }
  // Number of matched readers (for clients that want to wait for the daemon).
  int matched() const {
    dds_publication_matched_status_t st{};
    return dds_get_publication_matched_status(entity_.get(), &st) >= 0
               ? static_cast<int>(st.current_count)
               : 0;
  }
  dds_entity_t get() const { return entity_.get(); }

 private:
  Entity entity_;
};

template <class T>
class Reader {
 public:
  Reader(Participant& p, const char* topic, const dds_topic_descriptor_t* desc,
         const QosSpec& qos) {
    const Qos q(qos);
    const dds_entity_t r =
        dds_create_reader(p.subscriber(), p.topic(topic, desc, qos), q.get(), nullptr);
    if (r < 0) throw DdsError(std::string("create reader ") + topic, r);
    entity_ = Entity(r);
    waitset_ = Entity(dds_create_waitset(p.get()));
    condition_ = Entity(dds_create_readcondition(r, DDS_ANY_STATE));
    dds_waitset_attach(waitset_.get(), condition_.get(), 0);
  }
  Reader(Participant& p, const Topic<T>& t) : Reader(p, t.name.c_str(), t.type, t.qos) {}

  // Waits up to timeout for data; true when samples may be taken.
  bool wait(std::chrono::nanoseconds timeout) {
    dds_attach_t triggered = 0;
    return dds_waitset_wait(waitset_.get(), &triggered, 1, timeout.count()) > 0;
  }

  // Takes every available valid sample and calls f(const T&) on each; returns the count.
  // Samples are loaned from Cyclone and returned before take_each returns.
  template <class F>
  int take_each(F&& f) {
    return take_each_with_info([&](const T& sample, const dds_sample_info_t&) { f(sample); });
  }
  // The same with each sample's info (f(const T&, const dds_sample_info_t&)): who wrote it.
  template <class F>
  int take_each_with_info(F&& f) {
    int count = 0;
    for (;;) {
      void* samples[16] = {};
      dds_sample_info_t infos[16];
      const dds_return_t n = dds_take(entity_.get(), samples, infos, 16, 16);
      if (n <= 0) break;
      for (dds_return_t i = 0; i < n; ++i) {
        if (infos[i].valid_data) {
          f(*static_cast<const T*>(samples[i]), infos[i]);
          ++count;
        }
      }
      dds_return_loan(entity_.get(), samples, n);
    }
    return count;
  }
  // wait() also returns when `other` (another reader of the participant) has data.
  void also_wake_on(dds_entity_t other) {
    others_.emplace_back(dds_create_readcondition(other, DDS_ANY_STATE));
    dds_waitset_attach(waitset_.get(), others_.back().get(), 0);
  }
  void wake() { dds_waitset_set_trigger(waitset_.get(), true); }
  void clear_wake() { dds_waitset_set_trigger(waitset_.get(), false); }
  // Number of matched writers (for clients that want to wait for the daemon).
  int matched() const {
    dds_subscription_matched_status_t st{};
    return dds_get_subscription_matched_status(entity_.get(), &st) >= 0
               ? static_cast<int>(st.current_count)
               : 0;
  }
  dds_entity_t get() const { return entity_.get(); }

 private:
  Entity entity_;
  Entity waitset_;
  Entity condition_;
  std::vector<Entity> others_;
};

}  // namespace rangefit::dds
