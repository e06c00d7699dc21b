#pragma once
// The scan pipeline: a bounded request queue and one worker thread that, per request, runs the
// scan (HAL devices → fusion, behind ScanBackend), detects (behind Detector), spools the cloud
// and result, and only then hands them to the sink (the DDS layer). Driver threads live inside
// the backend and are never blocked by detection. A full queue answers busy; nothing is dropped
// silently. Anything a backend or detector throws becomes an error result; the worker survives.

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "daemon/service/lifecycle.hpp"
#include "daemon/service/scan_sensor.hpp"
#include "daemon/service/scan_types.hpp"
#include "daemon/service/spool.hpp"
#include "detect/common/point_cloud.hpp"
#include "hal/device.hpp"
#include "hal/time.hpp"

namespace rangefit::daemon {

struct NamedHealth {
  std::string name;
  hal::DeviceHealth health;
};

// One sensor's own scan among several a request fused (sensors): as that sensor took it (world
// frame, organised when the sensor is), with what it knows about its rays.
struct SensorScan {
  std::string name;  // the device
  PointCloud cloud;
  ScanSensor sensor;
};

struct ScanOutcome {
  ScanOutcome() = default;
  ScanOutcome(hal::Status s, PointCloud c, ScanSensor view = {}, std::int64_t acquired = 0)
      : status(std::move(s)),
        cloud(std::move(c)),
        sensor(std::move(view)),
        acquired_wall_ns(acquired) {}

  hal::Status status;  // not ok: the scan failed (device gone, timeout, cancelled)
  PointCloud cloud;    // world frame, mm
  ScanSensor sensor;   // what the sensor knows about its rays, world frame
  // Wall-clock time (ns since the Unix epoch) the scan's last sample was taken; 0: unknown
  // (the result is then stamped when it is published).
  std::int64_t acquired_wall_ns = 0;
  // Each sensor's scan apart, when the request fused several and its detection needs them apart
  // (the cameras of a stripe calibration: each is solved on its own sweep); else empty.
  std::vector<SensorScan> views;
};

class ScanBackend {
 public:
  virtual ~ScanBackend() = default;
  // Runs the scan the request describes. Must return soon after *cancel becomes true and call
  // progress() whenever data arrives, so the watchdog can tell a stalled scan from a slow one.
  virtual ScanOutcome scan(const ScanRequest& request, const std::atomic<bool>& cancel,
                           const std::function<void()>& progress) = 0;
  virtual std::vector<NamedHealth> health() const = 0;
};

class Detector {
 public:
  virtual ~Detector() = default;
  // Fills found/reason/parts/bore_radius_mm; the pipeline fills ids, counts and timings. views:
  // the scan's sensors apart (ScanOutcome::views), empty unless the request needs them.
  virtual DetectionResult detect(const PointCloud& cloud, const ScanRequest& request,
                                 const ScanSensor& sensor, std::span<const SensorScan> views) = 0;
};

class ResultSink {
 public:
  virtual ~ResultSink() = default;
  virtual void on_cloud(const ScanRequest& request, const PointCloud& cloud) = 0;
  virtual void on_result(const DetectionResult& result) = 0;
  virtual void on_state(LifecycleState state, const std::string& detail,
                        const std::string& active_id, std::size_t queue_depth) = 0;
};

enum class Submit { kAccepted, kBusy, kStopping };

struct PipelineOptions {
  std::size_t queue_capacity = 4;  // waiting requests; the running one is not counted
  // A scan running longer is cancelled and answered "scan timeout"; 0 = no limit.
  hal::Duration scan_timeout{0};
  // A detection running longer is answered "detection timeout" at once; the worker then waits
  // for the detector to return (detect/ cannot be interrupted) before the next request, without
  // feeding the watchdog. 0 = no limit.
  hal::Duration detect_timeout{0};
};

class Pipeline {
 public:
  // spool may be null (tests, replay); clock drives progress stamps (a fake one in tests).
  Pipeline(PipelineOptions options, ScanBackend& backend, Detector& detector, Spool* spool,
           ResultSink& sink, hal::Clock& clock);
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  Submit submit(ScanRequest request);
  // Stops the worker: the running scan finishes (abort = false) or is cancelled (abort = true);
  // queued requests are answered with an error result. Idempotent.
  void stop(bool abort);

  // Last time the worker made progress (loop iteration or data in a scan). A healthy idle
  // pipeline advances this every ~100 ms.
  hal::Timestamp last_progress() const { return hal::Timestamp(last_progress_ns_.load()); }
  bool stalled(hal::Timestamp now, hal::Duration limit) const {
    return now - last_progress() > limit;
  }

  std::size_t queue_depth() const;
  LifecycleState state() const { return state_.load(); }
  std::string last_error() const;
  std::uint64_t completed() const { return completed_.load(); }
  std::uint64_t rejected_busy() const { return busy_.load(); }
  void set_options(PipelineOptions options);  // SIGHUP: new queue bound and timeout
  // SIGHUP without losing requests: hold() keeps the worker from starting another request (new
  // ones still queue, or are answered busy); idle() is true once a held worker is between
  // requests; take_queue() hands the waiting requests over unanswered, for the next pipeline.
  void hold();
  bool idle() const;
  std::deque<ScanRequest> take_queue();

 private:
  void run();
  void process(const ScanRequest& request);
  ScanOutcome run_scan(const ScanRequest& request, bool* timed_out);
  DetectionResult run_detection(const ScanOutcome& scan, const ScanRequest& request);
  void set_state(LifecycleState s, const std::string& detail, const std::string& active);
  void touch() { last_progress_ns_.store(clock_.now().count()); }

  PipelineOptions options_;
  ScanBackend& backend_;
  Detector& detector_;
  Spool* spool_;
  ResultSink& sink_;
  hal::Clock& clock_;

  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<ScanRequest> queue_;
  bool stopping_ = false;
  bool held_ = false;
  bool processing_ = false;  // the worker took a request and has not finished it
  std::atomic<bool> cancel_{false};
  std::atomic<std::int64_t> last_progress_ns_{0};
  std::atomic<LifecycleState> state_{LifecycleState::kStarting};
  std::atomic<std::uint64_t> completed_{0};
  std::atomic<std::uint64_t> busy_{0};
  std::string last_error_;
  std::future<DetectionResult> pending_detection_;  // a timed-out detection still running
  std::thread worker_;
};

}  // namespace rangefit::daemon
