#pragma once
// The ScanBackend rangefitd runs with: DeviceBackend dispatches each request to the configured
// device's driver: "sim" runs the simulated cell through fusion (daemon/cell/sim_cell.hpp),
// "real" the cell's drivers (daemon/cell/real_devices.hpp); "replay" returns a recorded cloud
// (PLY) as the scan, replaying a spooled or simulated scan through the full pipeline and DDS as
// fast as possible (benchmarks, offline checks).

#include <map>
#include <memory>
#include <mutex>

#include "daemon/cell/cell_devices.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/pipeline.hpp"

namespace rangefit::daemon {

class DeviceBackend final : public ScanBackend {
 public:
  // Throws std::runtime_error when a simulated device's scene cannot be loaded.
  explicit DeviceBackend(CellConfig config);
  ScanOutcome scan(const ScanRequest& request, const std::atomic<bool>& cancel,
                   const std::function<void()>& progress) override;
  std::vector<NamedHealth> health() const override;

 private:
  ScanOutcome scan_views(const ScanRequest& request, const std::atomic<bool>& cancel,
                         const std::function<void()>& progress);
  ScanOutcome replay(const DeviceConfig& device, const std::function<void()>& progress);

  CellConfig config_;
  mutable std::mutex mutex_;
  std::map<std::string, hal::DeviceHealth> health_;
  std::map<std::string, PointCloud> replay_cache_;
  std::unique_ptr<CellDevices> sim_;   // when a device uses driver = "sim"
  std::unique_ptr<CellDevices> real_;  // when a device uses driver = "real"
};

}  // namespace rangefit::daemon
