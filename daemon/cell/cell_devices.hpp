#pragma once
// What DeviceBackend asks of a set of scanning devices, whatever drives them: the simulated cell
// (sim_cell.hpp) or the cell's drivers (real_devices.hpp). Behind this interface a build without
// the simulator (RANGEFIT_WITH_SIM=OFF) has no reference to it.

#include <atomic>
#include <functional>
#include <span>
#include <vector>

#include "daemon/service/config.hpp"
#include "daemon/service/pipeline.hpp"

namespace rangefit::daemon {

class CellDevices {
 public:
  virtual ~CellDevices() = default;
  // Scans with `device` (one of this set) as `request` plans it. Never throws: a device problem
  // is an error status in the outcome.
  virtual ScanOutcome scan(const DeviceConfig& device, const ScanRequest& request,
                           const std::atomic<bool>& cancel,
                           const std::function<void()>& progress) = 0;
  // Scans with several devices of this set, of one kind and configured sweep, at once where their
  // kind can: the cameras of one laser plane sweep together, so the axis moves once. One outcome
  // per device, in order, each as scan() would give it. Empty when these devices cannot scan
  // together (a kind that scans alone, another scene, axis or head): the caller then scans them
  // in turn.
  virtual std::vector<ScanOutcome> scan_together(std::span<const DeviceConfig* const> devices,
                                                 const ScanRequest& request,
                                                 const std::atomic<bool>& cancel,
                                                 const std::function<void()>& progress) = 0;
  virtual std::vector<NamedHealth> health() const = 0;
};

}  // namespace rangefit::daemon
