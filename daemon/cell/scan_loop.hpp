#pragma once
// What every scan shares, real (real_devices.cpp) or simulated (sim_cell.cpp): the
// read-fuse-watch loop over a sensor's stream and the stream of the device that moves it, the
// stripe cell's two-leg sweep, the edges of a sweep the daemon only watches, and the step that
// puts the fused scan into the world frame.

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "daemon/service/config.hpp"
#include "daemon/service/device_extrinsics.hpp"
#include "daemon/service/pipeline.hpp"
#include "daemon/service/scan_sensor.hpp"
#include "fusion/fused_scan.hpp"
#include "fusion/profile_assembler.hpp"
#include "hal/source.hpp"

namespace rangefit::daemon {

// Each paced read waits at most this long, so cancellation and health checks stay prompt.
inline constexpr hal::Duration kScanReadSlice = std::chrono::milliseconds(100);

enum class ScanLoopEnd { kDone, kCancelled, kFailed };

// What a scan loop answers to: the request's cancel flag and the pipeline's progress callback.
struct ScanControl {
  const std::atomic<bool>& cancel;
  const std::function<void()>& progress;
};

// Until done() holds: reads `paced` for up to one slice and takes what `drained` has queued,
// hands both batches to fuse(paced_batch, drained_batch), reports progress when anything
// arrived, then healthy(&why) checks the devices. kCancelled (*why = "cancelled") and kFailed
// (healthy() said why) leave stopping any motion to the caller.
template <class Paced, class Drained, class Done, class Fuse, class Healthy>
ScanLoopEnd run_scan_loop(hal::SampleSource<Paced>& paced, hal::SampleSource<Drained>& drained,
                          const ScanControl& control, Done&& done, Fuse&& fuse, Healthy&& healthy,
                          std::string* why) {
  std::vector<Paced> paced_batch;
  std::vector<Drained> drained_batch;
  while (!done()) {
    if (control.cancel) {
      *why = "cancelled";
      return ScanLoopEnd::kCancelled;
    }
    paced_batch.clear();
    drained_batch.clear();
    paced.read(paced_batch, kScanReadSlice);
    drained.read(drained_batch, hal::Duration::zero());
    fuse(paced_batch, drained_batch);
    if (!paced_batch.empty() || !drained_batch.empty()) control.progress();
    if (!healthy(why)) return ScanLoopEnd::kFailed;
  }
  return ScanLoopEnd::kDone;
}

// The stripe cell's sweep (thesis 5.2.1) once the axis is on its way to the sweep's start: that
// approach is watched but not fused; then start_sweep() (begin the assembler, start the ranger,
// command the sweep; a refusal is kFailed with *why set) and every axis sample and profile is
// fused until the axis reports the motion complete.
template <class StartSweep, class Healthy>
ScanLoopEnd sweep_stripe(hal::LinearAxis& axis, hal::RangerSource& ranger,
                         fusion::StripeCellAssembler& assembler, const ScanControl& control,
                         StartSweep&& start_sweep, Healthy&& healthy, std::string* why) {
  const auto done = [&axis] { return axis.motion_complete(); };
  ScanLoopEnd end = run_scan_loop(
      axis, ranger, control, done, [](const auto&, const auto&) {}, healthy, why);
  if (end != ScanLoopEnd::kDone) return end;
  if (!start_sweep(why)) return ScanLoopEnd::kFailed;
  const auto fuse = [&assembler](const std::vector<hal::AxisSample>& samples,
                                 const std::vector<hal::RangerProfile>& profiles) {
    for (const auto& s : samples) assembler.add_axis(s);
    for (const auto& p : profiles) assembler.add_profile(p);
  };
  return run_scan_loop(axis, ranger, control, done, fuse, healthy, why);
}

// A sweep -half .. +half (rad, about its zero) that another program drives (the robot pivoting
// the CSS, eq. 4.21; the cell panning the head, eq. 5.7): it has begun once the angle reached
// -half and is over once, after that, the angle reaches +half.
struct SweepEdges {
  double half = 0.0;
  bool at_start = false;
  bool at_end = false;
  void see(double angle) {
    constexpr double kSlack = 1e-4;  // rad
    at_start = at_start || angle <= -half + kSlack;
    at_end = at_start && angle >= half - kSlack;
  }
};


// The fused scan in the world frame, p_world = device_extrinsics(device) * T_mount_sensor *
// p_sensor, with the sensor (given in fusion's frame) moved along; a scan fusion marked bad is an
// error naming the device. With the devices' clock, the last sample's stamp is put on the wall
// clock (the offset between the two read once, here).
ScanOutcome finish_scan(const DeviceConfig& device, fusion::FusedScan scan,
                        const Eigen::Isometry3d& T_mount_sensor = Eigen::Isometry3d::Identity(),
                        const ScanSensor& sensor = {}, const hal::Clock* clock = nullptr);

// t (of clock) on the wall clock, ns since the Unix epoch.
std::int64_t wall_ns(hal::Timestamp t, const hal::Clock& clock);

}  // namespace rangefit::daemon
