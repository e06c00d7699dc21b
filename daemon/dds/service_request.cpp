#include "daemon/dds/service_request.hpp"

#include <cinttypes>
#include <cstdio>

#include "daemon/dds/messages.hpp"
#include "daemon/dds/service_body.hpp"

namespace rangefit::daemon {

std::string service_call_id(const rangefit_msgs_srv_dds__Detect_Request_& msg) {
  char id[64];  // "ros-" + 16 hex digits + "-" + at most 20 characters of a signed 64-bit number
  std::snprintf(id, sizeof id, "ros-%016" PRIx64 "-%" PRId64, msg.rmw_client_guid,
                msg.rmw_sequence_number);
  return id;
}

ScanRequest from_service_request(const rangefit_msgs_srv_dds__Detect_Request_& msg,
                                 std::string* error) {
  auto topic_request = service_body<rangefit_msgs_msg_dds__DetectRequest_>(msg);
  // The call's id goes in before decoding, so every check of from_msg runs on it (clearing a
  // "request_id is empty" error afterwards skipped the checks that follow that one).
  const std::string call_id = service_call_id(msg);
  if (msg.request_id == nullptr || msg.request_id[0] == '\0') {
    topic_request.request_id = const_cast<char*>(call_id.c_str());  // from_msg only reads it
  }
  return from_msg(topic_request, error);
}

}  // namespace rangefit::daemon
