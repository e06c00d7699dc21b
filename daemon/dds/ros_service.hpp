#pragma once
// The ROS 2 service /rangefit/detect (rangefit_msgs/srv/Detect) over plain DDS, framed as
// rmw_cyclonedds frames services (daemon/idl/rangefit_srvs.idl): requests on
// rq/rangefit/detectRequest, replies on rr/rangefit/detectReply, each reply carrying the
// request's client id and sequence number, so `ros2 service call` (and any rclcpp/rclpy client)
// gets its answer. Requests join the same validation and queue as rt/rangefit/detect_request;
// the answer is the Detection of the request, whichever way it was produced.

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>

#include "daemon/dds/dds.hpp"
#include "daemon/service/scan_types.hpp"
#include "rangefit_srvs.h"

namespace rangefit::daemon {

namespace topics {
inline constexpr const char* kServiceRequest = "rq/rangefit/detectRequest";
inline constexpr const char* kServiceReply = "rr/rangefit/detectReply";
dds::QosSpec service_qos();  // reliable, volatile, keep-all (ROS 2 services: reliable, volatile)
}  // namespace topics

class RosDetectService {
 public:
  // ns: the ROS namespace (rq/<ns>/rangefit/detectRequest). Throws dds::DdsError.
  explicit RosDetectService(dds::Participant& participant, const std::string& ns = "");

  // Takes every waiting service request and calls handle(request, error) for each, as
  // DdsService::poll_requests does; remembers who asked. Returns the number handled.
  int take(const std::function<void(ScanRequest, const std::string&)>& handle);
  // Replies to the service requests that asked for result.request_id (none: nothing to do).
  void answer(const DetectionResult& result, const std::string& frame);
  dds_entity_t reader() const { return requests_.get(); }
  dds_entity_t writer() const { return replies_.get(); }
  std::uint64_t write_failures() const { return write_failures_; }

 private:
  struct Caller {
    std::uint64_t client = 0;
    std::int64_t sequence = 0;
  };
  dds::Reader<rangefit_msgs_srv_dds__Detect_Request_> requests_;
  dds::Writer<rangefit_msgs_srv_dds__Detect_Response_> replies_;
  std::mutex mutex_;                                   // take() and answer() run on two threads
  std::map<std::string, std::deque<Caller>> waiting_;  // by request id
  std::size_t waiting_count_ = 0;
  std::uint64_t write_failures_ = 0;
};

}  // namespace rangefit::daemon
