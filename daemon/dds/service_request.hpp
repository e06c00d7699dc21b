#pragma once
// A /rangefit/detect service request (rangefit_msgs/srv/Detect, as rmw_cyclonedds frames it: the
// caller's request-writer id and sequence number, then the fields of DetectRequest.msg) read into
// the daemon's ScanRequest with the same checks as a request on rt/rangefit/detect_request.
// Pure: no DDS entities, so the fuzz harness runs exactly this decoding.

#include <string>

#include "daemon/service/scan_types.hpp"
#include "rangefit_srvs.h"

namespace rangefit::daemon {

// `ros2 service call` users need not invent ids: a request without one is named after the call,
// "ros-<client id, 16 hex digits>-<sequence number>". error: empty, or why the request is refused.
ScanRequest from_service_request(const rangefit_msgs_srv_dds__Detect_Request_& msg,
                                 std::string* error);

// The id given to a service request that carries none.
std::string service_call_id(const rangefit_msgs_srv_dds__Detect_Request_& msg);

}  // namespace rangefit::daemon
