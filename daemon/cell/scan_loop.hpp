#pragma once
// What every scan shares, real (real_devices.cpp) or simulated (sim_cell.cpp): the
// read-fuse-watch loop over a sensor's stream and the stream of the device that moves it, the
// stripe cell's two-leg sweep, the edges of a sweep the daemon only watches, and the step that
// puts the fused scan into the world frame.

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <functional>
#include <span>
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

// Until done() holds: reads `paced` for up to one slice and takes what each of `drained` has
// queued, hands the batches to fuse(paced_batch, drained_batches) (one batch per drained source,
// in order), reports progress when anything arrived, then healthy(&why) checks the devices.
// kCancelled (*why = "cancelled") and kFailed (healthy() said why) leave stopping any motion to
// the caller.
template <class Paced, class Drained, class Done, class Fuse, class Healthy>
ScanLoopEnd run_scan_loop(hal::SampleSource<Paced>& paced,
                          std::span<hal::SampleSource<Drained>* const> drained,
                          const ScanControl& control, Done&& done, Fuse&& fuse, Healthy&& healthy,
                          std::string* why) {
  std::vector<Paced> paced_batch;
  std::vector<std::vector<Drained>> drained_batches(drained.size());
  while (!done()) {
    if (control.cancel) {
      *why = "cancelled";
      return ScanLoopEnd::kCancelled;
    }
    paced_batch.clear();
    paced.read(paced_batch, kScanReadSlice);
    bool arrived = !paced_batch.empty();
    for (std::size_t k = 0; k < drained.size(); ++k) {
      drained_batches[k].clear();
      drained[k]->read(drained_batches[k], hal::Duration::zero());
      arrived = arrived || !drained_batches[k].empty();
    }
    fuse(paced_batch, std::span<const std::vector<Drained>>(drained_batches));
    if (arrived) control.progress();
    if (!healthy(why)) return ScanLoopEnd::kFailed;
  }
  return ScanLoopEnd::kDone;
}

// The same loop over one drained stream: fuse(paced_batch, drained_batch).
template <class Paced, class Drained, class Done, class Fuse, class Healthy>
ScanLoopEnd run_scan_loop(hal::SampleSource<Paced>& paced, hal::SampleSource<Drained>& drained,
                          const ScanControl& control, Done&& done, Fuse&& fuse, Healthy&& healthy,
                          std::string* why) {
  hal::SampleSource<Drained>* const one[] = {&drained};
  return run_scan_loop(
      paced, std::span<hal::SampleSource<Drained>* const>(one), control, done,
      [&fuse](const std::vector<Paced>& p, std::span<const std::vector<Drained>> d) {
        fuse(p, d[0]);
      },
      healthy, why);
}

// One camera of a stripe sweep: its ranger's profiles and the assembler that fuses them with the
// axis samples. Several cameras of one laser plane sweep together: the axis moves once.
struct StripeCamera {
  hal::RangerSource* ranger;
  fusion::StripeCellAssembler* assembler;
};

// The stripe cell's sweep (thesis 5.2.1) once the axis is on its way to the sweep's start: that
// approach is watched but not fused; then start_sweep() (begin the assemblers, start the rangers,
// command the sweep; a refusal is kFailed with *why set) and every axis sample goes to every
// camera's assembler, with that camera's profiles, until the axis reports the motion complete.
template <class StartSweep, class Healthy>
ScanLoopEnd sweep_stripe(hal::LinearAxis& axis, std::span<const StripeCamera> cameras,
                         const ScanControl& control, StartSweep&& start_sweep, Healthy&& healthy,
                         std::string* why) {
  std::vector<hal::RangerSource*> rangers;
  for (const StripeCamera& c : cameras) rangers.push_back(c.ranger);
  const std::span<hal::RangerSource* const> drained(rangers);
  const auto done = [&axis] { return axis.motion_complete(); };
  ScanLoopEnd end = run_scan_loop(
      axis, drained, control, done, [](const auto&, const auto&) {}, healthy, why);
  if (end != ScanLoopEnd::kDone) return end;
  if (!start_sweep(why)) return ScanLoopEnd::kFailed;
  const auto fuse = [&cameras](const std::vector<hal::AxisSample>& samples,
                               std::span<const std::vector<hal::RangerProfile>> profiles) {
    for (std::size_t k = 0; k < cameras.size(); ++k) {
      for (const auto& s : samples) cameras[k].assembler->add_axis(s);
      for (const auto& p : profiles[k]) cameras[k].assembler->add_profile(p);
    }
  };
  return run_scan_loop(axis, drained, control, done, fuse, healthy, why);
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
