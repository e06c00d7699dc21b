#pragma once
// driver = "sim": the simulated cell on the same path as the hardware. Per scan, the sim/ devices
// of the requested sensor stream into the fusion/ assembler exactly as the real drivers would,
// as the sensor's kind says (its SimSensor, daemon/cell/sensors/sim/<kind>.cpp):
//   css      - sim::CssRig: CSS revolutions + the robot's last-joint stream → CssAssembler;
//   stripe   - sim::StripeCell: ranger profiles + linear-axis samples → StripeCellAssembler;
//   pan_tilt - sim::PanTiltHead: ranger profiles + pan/tilt samples → PanTiltAssembler.
// The request's scan plan sets the motion (sweep range and speed), the [fusion] table the
// geometry both the devices and the assemblers use. While the scan runs the loop watches the
// devices' health: a link lost mid-scan ends the scan with an error and leaves the device
// reported as disconnected until its next scan starts streaming again.
//
// Frames: fusion builds each sensor's own world frame; the scene's [sensors.*] mount places it in
// the scene and the device's xyz_mm/rpy_rad extrinsics, when set, place the scene in the world:
// p_world = T(xyz, rpy) * T_scene_sensor * p_sensor.

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "daemon/cell/cell_devices.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/pipeline.hpp"

#include "sim/fault_options.hpp"

namespace rangefit::sim {
class SimClock;
}  // namespace rangefit::sim

namespace rangefit::daemon {

class SimCell final : public CellDevices {
 public:
  // Loads the scene of every simulated scanning device; throws std::runtime_error naming the
  // device and the file when one cannot be loaded (start-up or reload, never mid-scan).
  // The devices' clock is a sim::SimClock at sim.time_scale, or the one given.
  explicit SimCell(const CellConfig& config);
  SimCell(const CellConfig& config, std::unique_ptr<sim::SimClock> clock);
  ~SimCell();
  SimCell(const SimCell&) = delete;
  SimCell& operator=(const SimCell&) = delete;

  // device.driver must be kSim. request.sweep_* are in internal units (mm or rad).
  ScanOutcome scan(const DeviceConfig& device, const ScanRequest& request,
                   const std::atomic<bool>& cancel, const std::function<void()>& progress) override;
  // Devices over one scene whose kind scans together: one StripeCell or PanTiltHead with every
  // camera.
  std::vector<ScanOutcome> scan_together(std::span<const DeviceConfig* const> devices,
                                         const ScanRequest& request,
                                         const std::atomic<bool>& cancel,
                                         const std::function<void()>& progress) override;
  // One entry per simulated HAL device: "<name>" (the sensor) and "<name>/joint", "/axis" or
  // "/angles" (the stream that moves it).
  std::vector<NamedHealth> health() const override;

  struct LoadedScene;
  struct Run;  // one scan in progress, as the kinds' scans (daemon/cell/sim_sensor.hpp) see it

 private:
  CellConfig config_;
  std::unique_ptr<sim::SimClock> clock_;
  std::map<std::string, std::shared_ptr<LoadedScene>> scenes_;  // by device name
  std::map<std::string, int> scans_;                            // scans started, by device
  mutable std::mutex mutex_;
  std::map<std::string, hal::DeviceHealth> health_;
  std::map<std::string, hal::StreamCounters> totals_;  // of finished scans, by health name

  // Counts a scan of the device: its noise seed and the faults [devices.sim_fault] puts on it.
  std::pair<std::uint64_t, sim::FaultOptions> next_scan(const DeviceConfig& device);
  // A scan of the device starts: counted, with the counters of the scans before it.
  Run start_run(const DeviceConfig& device, const ScanRequest& request,
                const std::atomic<bool>& cancel, const std::function<void()>& progress,
                const LoadedScene& scene);
};

}  // namespace rangefit::daemon
