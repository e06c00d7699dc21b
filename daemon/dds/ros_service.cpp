#include "daemon/dds/ros_service.hpp"

#include "daemon/dds/messages.hpp"
#include "daemon/dds/service_body.hpp"
#include "daemon/dds/service_request.hpp"
#include "daemon/dds/topics.hpp"

namespace rangefit::daemon {
namespace {

// Callers waiting for an answer; every request is answered, so this only bounds a flood.
constexpr std::size_t kMaxWaiting = 4096;

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
    std::string error;
    ScanRequest req = from_service_request(m, &error);
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
  const auto reply = service_sample<rangefit_msgs_srv_dds__Detect_Response_>(
      caller.client, caller.sequence, out.msg());
  if (!replies_.write(reply)) ++write_failures_;
}

}  // namespace rangefit::daemon
