#pragma once
// ScanBackend and Detector implementations rangefitd runs with.
// - DeviceBackend dispatches each request to the configured device's driver: "sim" runs the
//   simulated cell through fusion (daemon/sim_cell.hpp), "real" the cell's drivers
//   (daemon/real_devices.hpp); "replay" returns a recorded cloud (PLY)
//   as the scan, replaying a spooled or simulated scan through the full pipeline and DDS as fast
//   as possible (benchmarks, offline checks).
// - ModelDetector runs the thesis detectors of detect/ with the options the detection adapter
//   (daemon/detection_adapter.hpp) makes of the request, the configured model and what the
//   scan's sensor knows, and reports their found/reason unchanged (no gate of its own).

#include <map>
#include <mutex>

#include "daemon/config.hpp"
#include "daemon/pipeline.hpp"
#include "daemon/real_devices.hpp"
#include "daemon/sim_cell.hpp"

namespace rangefit::daemon {

class DeviceBackend final : public ScanBackend {
 public:
  // Throws std::runtime_error when a simulated device's scene cannot be loaded.
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
  std::unique_ptr<SimCell> sim_;       // when a device uses driver = "sim"
  std::unique_ptr<RealDevices> real_;  // when a device uses driver = "real"
};

class ModelDetector final : public Detector {
 public:
  explicit ModelDetector(DaemonConfig config) : config_(std::move(config)) {}
  DetectionResult detect(const PointCloud& cloud, const ScanRequest& request,
                         const ScanSensor& sensor) override;

 private:
  DetectionResult detect_object_request(const PointCloud& cloud, const ScanRequest& request,
                                        const ScanSensor& sensor);
  DetectionResult detect_bore_request(const PointCloud& cloud, const ScanRequest& request,
                                      const ScanSensor& sensor);
  DaemonConfig config_;
};

}  // namespace rangefit::daemon
