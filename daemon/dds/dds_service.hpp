#pragma once
// rangefitd's DDS face: the writers and the request reader of the topic table
// (daemon/dds/topics.hpp), which the clients (daemon/dds/client.hpp) open too.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "daemon/dds/dds.hpp"
#include "daemon/dds/messages.hpp"
#include "daemon/dds/reply_gate.hpp"
#include "daemon/dds/ros_discovery.hpp"
#include "daemon/dds/ros_service.hpp"
#include "daemon/dds/topics.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/pipeline.hpp"

namespace rangefit::daemon {

class DdsService final : public ResultSink {
 public:
  // Throws dds::DdsError when the domain or an entity cannot be created, std::runtime_error
  // when a [dds.security] document cannot be read (start-up only). The participant runs with
  // config.config_uri (else the process' CYCLONEDDS_URI) and, when on, the security settings.
  explicit DdsService(const DdsConfig& config);

  void on_cloud(const ScanRequest& request, const PointCloud& cloud) override;
  void on_result(const DetectionResult& result) override;
  void on_state(LifecycleState state, const std::string& detail, const std::string& active_id,
                std::size_t queue_depth) override;
  void publish_diagnostics(std::vector<DiagStatus> statuses);
  // The frames of `config` ([frames]) for every header from now on, its sensors' mounts on
  // rt/tf_static and its object models on rt/rangefit/models (their shapes for the meshes on
  // rt/rangefit/markers). At start-up and after each reload.
  void publish_frames(const DaemonConfig& config);

  // Waits up to timeout for requests and calls handle(request, error) for each one taken; error
  // is non-empty when the message is malformed. Returns the number handled.
  int poll_requests(std::chrono::nanoseconds timeout,
                    const std::function<void(ScanRequest, const std::string&)>& handle);

  std::uint64_t write_failures() const { return write_failures_ + service_.write_failures(); }

 private:
  void count(bool ok) { write_failures_ += ok ? 0 : 1; }

  dds::Participant participant_;
  std::mutex mutex_;  // writers are used from the pipeline worker and the main loop
  topics::Writer<topics::Cloud> cloud_;
  topics::Writer<topics::Detections> detections_;
  topics::Writer<topics::Pose> pose_;
  topics::Writer<topics::State> state_;
  topics::Writer<topics::Diagnostics> diagnostics_;
  topics::Reader<topics::Request> requests_;
  topics::Writer<topics::Poses> poses_;
  topics::Writer<topics::Tf> tf_;
  topics::Writer<topics::Tf> tf_static_;
  topics::Writer<topics::Models> models_;
  topics::Writer<topics::Detections3d> detections3d_;
  topics::Writer<topics::Markers> markers_;
  RosDetectService service_;
  ReplyGate reply_gate_;      // an answer waits (bounded) for its requester's result reader
  RosDiscovery discovery_;    // the node on ros_discovery_info: after every other entity
  std::string frame_prefix_;  // "<ros namespace>/" before every frame id; empty without one
  FramesConfig frames_;       // guarded by mutex_; ids with the prefix
  std::map<std::string, ObjectModel> shapes_;  // the models' parts by model name; mutex_
  std::uint64_t write_failures_ = 0;
};

}  // namespace rangefit::daemon
