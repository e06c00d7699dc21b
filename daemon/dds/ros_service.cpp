#include "daemon/dds/ros_service.hpp"

#include <fmt/format.h>

#include "daemon/dds/messages.hpp"
#include "daemon/dds/topics.hpp"

namespace rangefit::daemon {
namespace {

// Callers waiting for an answer; every request is answered, so this only bounds a flood.
constexpr std::size_t kMaxWaiting = 4096;

// The service request minus its header, as the topic's type (the fields are the same, in order).
rangefit_msgs_msg_dds__DetectRequest_ as_topic_request(
    const rangefit_msgs_srv_dds__Detect_Request_& m) {
  rangefit_msgs_msg_dds__DetectRequest_ r{};
  r.request_id = m.request_id;
  r.kind = m.kind;
  r.model = m.model;
  r.bore_position = m.bore_position;
  r.bore_axis = m.bore_axis;
  r.bore_radius = m.bore_radius;
  r.sensor = m.sensor;
  r.sweep_start = m.sweep_start;
  r.sweep_end = m.sweep_end;
  r.sweep_speed = m.sweep_speed;
  r.bore_plane_normal = m.bore_plane_normal;
  r.instances = m.instances;
  r.hypotheses = m.hypotheses;
  r.trials = m.trials;
  r.seed = m.seed;
  r.bore_outer_radius = m.bore_outer_radius;
  r.bore_walls = m.bore_walls;
  r.bore_normal_keep = m.bore_normal_keep;
  r.view_dir = m.view_dir;
  r.sensor_position_given = m.sensor_position_given;
  r.sensor_position = m.sensor_position;
  r.parts = m.parts;
  r.target = m.target;
  r.target_edge = m.target_edge;
  r.target_bar = m.target_bar;
  r.target_pose = m.target_pose;
  r.bore_half_angle = m.bore_half_angle;
  r.bore_cylinder_radius = m.bore_cylinder_radius;
  r.bore_radius2 = m.bore_radius2;
  r.bore_major_axis = m.bore_major_axis;
  return r;
}

}  // namespace

namespace topics {
dds::QosSpec service_qos() { return {true, false, 10, true, 1024}; }
}  // namespace topics

RosDetectService::RosDetectService(dds::Participant& participant, const std::string& ns)
    : requests_(participant, topics::in_namespace(topics::kServiceRequest, ns).c_str(),
                &rangefit_msgs_srv_dds__Detect_Request__desc, topics::service_qos()),
      replies_(participant, topics::in_namespace(topics::kServiceReply, ns).c_str(),
               &rangefit_msgs_srv_dds__Detect_Response__desc, topics::service_qos()) {}

int RosDetectService::take(const std::function<void(ScanRequest, const std::string&)>& handle) {
  return requests_.take_each([&](const rangefit_msgs_srv_dds__Detect_Request_& m) {
    const auto topic_request = as_topic_request(m);
    std::string error;
    ScanRequest req = from_msg(topic_request, &error);
    // `ros2 service call` users need not invent ids: the call's identity is one.
    if (req.id.empty()) {
      req.id = fmt::format("ros-{:016x}-{}", m.rmw_client_guid, m.rmw_sequence_number);
      if (error == "request_id is empty") error.clear();
    }
    {
      std::lock_guard lock(mutex_);
      if (waiting_count_ >= kMaxWaiting) return;  // a flood: no one can be answered in time
      waiting_[req.id].push_back({m.rmw_client_guid, m.rmw_sequence_number});
      ++waiting_count_;
    }
    handle(std::move(req), error);
  });
}

void RosDetectService::answer(const DetectionResult& result, const std::string& frame) {
  Caller caller;
  {
    std::lock_guard lock(mutex_);
    const auto it = waiting_.find(result.request_id);
    if (it == waiting_.end()) return;
    caller = it->second.front();
    it->second.pop_front();
    if (it->second.empty()) waiting_.erase(it);
    --waiting_count_;
  }
  const DetectionOut out(result, frame);
  const auto& d = out.msg();
  rangefit_msgs_srv_dds__Detect_Response_ reply{};
  reply.rmw_client_guid = caller.client;
  reply.rmw_sequence_number = caller.sequence;
  reply.header = d.header;
  reply.request_id = d.request_id;
  reply.kind = d.kind;
  reply.found = d.found;
  reply.reason = d.reason;
  reply.model = d.model;
  reply.part_names = d.part_names;
  reply.poses = d.poses;
  reply.bore_radius = d.bore_radius;
  reply.scores = d.scores;
  reply.num_points = d.num_points;
  reply.scan_seconds = d.scan_seconds;
  reply.detect_seconds = d.detect_seconds;
  reply.spool_entry = d.spool_entry;
  reply.part_instances = d.part_instances;
  reply.details = d.details;
  if (!replies_.write(reply)) ++write_failures_;
}

}  // namespace rangefit::daemon
