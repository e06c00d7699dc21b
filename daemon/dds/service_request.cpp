#include "daemon/dds/service_request.hpp"

#include <cinttypes>
#include <cstdio>

#include "daemon/dds/messages.hpp"

namespace rangefit::daemon {
namespace {

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

std::string service_call_id(const rangefit_msgs_srv_dds__Detect_Request_& msg) {
  char id[64];  // "ros-" + 16 hex digits + "-" + at most 20 characters of a signed 64-bit number
  std::snprintf(id, sizeof id, "ros-%016" PRIx64 "-%" PRId64, msg.rmw_client_guid,
                msg.rmw_sequence_number);
  return id;
}

ScanRequest from_service_request(const rangefit_msgs_srv_dds__Detect_Request_& msg,
                                 std::string* error) {
  auto topic_request = as_topic_request(msg);
  // The call's id goes in before decoding, so every check of from_msg runs on it (clearing a
  // "request_id is empty" error afterwards skipped the checks that follow that one).
  const std::string call_id = service_call_id(msg);
  if (msg.request_id == nullptr || msg.request_id[0] == '\0') {
    topic_request.request_id = const_cast<char*>(call_id.c_str());  // from_msg only reads it
  }
  return from_msg(topic_request, error);
}

}  // namespace rangefit::daemon
