#pragma once
// One running configuration of rangefitd: backend, detector, spool, pipeline and DDS entities,
// built from a DaemonConfig. The executable (daemon/rangefitd) owns signals and sd_notify and
// calls step() from its main loop; tests can run a Service in-process the same way.

#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "daemon/cell/device_backend.hpp"
#include "daemon/dds/dds_service.hpp"
#include "daemon/rangefitd/result_board.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/diagnostics.hpp"
#include "daemon/service/model_detector.hpp"
#include "daemon/service/pipeline.hpp"
#include "daemon/service/spool.hpp"

namespace rangefit::daemon {

class Service {
 public:
  // Throws std::runtime_error when the spool cannot be opened or DDS cannot start (start-up).
  // backend/detector: null to use DeviceBackend/ModelDetector built from the config.
  Service(DaemonConfig config, hal::Clock& clock, std::unique_ptr<ScanBackend> backend = nullptr,
          std::unique_ptr<Detector> detector = nullptr);
  ~Service();

  // Takes requests (waiting up to timeout) and publishes diagnostics when due, or at once when
  // a device or the pipeline changed state.
  void step(std::chrono::milliseconds timeout);
  // The one way into the queue, for DDS, HTTP and TCP requests alike (any thread): validates and
  // queues the request; nullopt when queued, else the error result it is answered with (bad
  // request, busy, stopping), published like every result. decode_error: the request could not
  // be decoded.
  std::optional<DetectionResult> admit(ScanRequest request, const std::string& decode_error = "");
  // What the HTTP and TCP interfaces read: results by id, state, diagnostics (any thread).
  ResultBoard& board() { return board_; }
  PipelineSnapshot snapshot() const;
  // The configured model of that name, the spool directory (any thread).
  std::optional<ObjectModel> model(const std::string& name) const;
  std::filesystem::path spool_directory() const;
  DaemonConfig config_copy() const;
  // SIGHUP: a config that changes nothing DDS-related is checked at once and swapped in between
  // scans: the running scan finishes with the old one while step() goes on taking requests, and
  // the waiting requests carry over to the new pipeline. Returns false with *why when the new
  // config is refused (nothing changes), true when it is in force or will be after the scan.
  bool reload(const DaemonConfig& next, std::string* why);
  bool reload_pending() const { return pending_ != nullptr; }
  void stop(bool abort) { pipeline_->stop(abort); }

  bool stalled() const;
  std::string status_line() const;  // for STATUS=
  hal::Timestamp last_progress() const { return pipeline_->last_progress(); }
  const DaemonConfig& config() const { return config_; }

 private:
  void build_pipeline();
  std::optional<DetectionResult> submit_locked(const ScanRequest& request);  // mutex_ held
  void apply_pending_reload();  // once the held pipeline is between scans

  struct PendingReload {
    DaemonConfig config;
    Spool spool;
    std::unique_ptr<ScanBackend> backend;
  };

  DaemonConfig config_;
  hal::Clock& clock_;
  std::unique_ptr<ScanBackend> backend_;
  std::unique_ptr<Detector> detector_;
  bool own_backend_;
  Spool spool_;
  DdsService dds_;
  ResultBoard board_{dds_};  // the pipeline's sink: records, then forwards to DDS
  // Guards config_, spool_ and pipeline_ against reload() for the interfaces' threads; the main
  // thread (step, reload) is their only writer.
  mutable std::mutex mutex_;
  std::unique_ptr<Pipeline> pipeline_;
  DiagnosticsBuilder diagnostics_;
  hal::Timestamp next_diagnostics_{0};
  std::vector<int> published_states_;  // the states of the last rt/diagnostics (step)
  std::unique_ptr<PendingReload> pending_;
};

}  // namespace rangefit::daemon
