#pragma once
// ScanBackend and Detector implementations rangefitd runs with.
// - DeviceBackend dispatches each request to the configured device's driver. The replay driver
//   returns a recorded cloud (PLY) as the scan: it replays a spooled or simulated scan through
//   the full pipeline and DDS as fast as possible (benchmarks, offline checks).
// - ModelDetector runs the thesis detectors of detect/ with the configured parameters.

#include <map>
#include <mutex>

#include "daemon/config.hpp"
#include "daemon/pipeline.hpp"

namespace rangefit::daemon {

class DeviceBackend final : public ScanBackend {
 public:
  explicit DeviceBackend(DaemonConfig config);
  ScanOutcome scan(const ScanRequest& request, const std::atomic<bool>& cancel,
                   const std::function<void()>& progress) override;
  std::vector<NamedHealth> health() const override;

 private:
  ScanOutcome replay(const DeviceConfig& device, const std::function<void()>& progress);

  DaemonConfig config_;
  mutable std::mutex mutex_;
  std::map<std::string, hal::DeviceHealth> health_;
  std::map<std::string, PointCloud> replay_cache_;
};

class ModelDetector final : public Detector {
 public:
  explicit ModelDetector(DaemonConfig config) : config_(std::move(config)) {}
  DetectionResult detect(const PointCloud& cloud, const ScanRequest& request) override;

 private:
  DetectionResult detect_object_request(const PointCloud& cloud, const ScanRequest& request);
  DetectionResult detect_bore_request(const PointCloud& cloud, const ScanRequest& request);
  DaemonConfig config_;
};

}  // namespace rangefit::daemon
