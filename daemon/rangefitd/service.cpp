#include "daemon/rangefitd/service.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "daemon/service/log_escape.hpp"
#include "daemon/service/request_validation.hpp"
#include "daemon/service/result_picture.hpp"

namespace rangefit::daemon {
namespace {

hal::Duration seconds(double s) {
  return std::chrono::duration_cast<hal::Duration>(std::chrono::duration<double>(s));
}

// picture.png of each spool entry, with the configured models' shapes for object results. Runs
// on the pipeline's worker, the one thread that draws.
Spool::PictureWriter picture_writer(const std::vector<ObjectModelConfig>& objects) {
  return [objects](const std::filesystem::path& path, const PointCloud& cloud,
                   const DetectionResult& result, std::string* error) {
    const ObjectModel* model = nullptr;
    for (const ObjectModelConfig& o : objects) {
      if (o.name == result.model) model = &o.model;
    }
    return write_result_picture(path, cloud, result, model, error);
  };
}

// The pipeline's state, whether it is stalled, and each device's state: what rt/diagnostics
// publishes at once when it changes.
std::vector<int> states_of(const PipelineSnapshot& snap, const std::vector<NamedHealth>& health) {
  std::vector<int> states{static_cast<int>(snap.state), snap.stalled ? 1 : 0};
  for (const NamedHealth& h : health) states.push_back(static_cast<int>(h.health.state));
  return states;
}

}  // namespace

Service::Service(DaemonConfig config, hal::Clock& clock, std::unique_ptr<ScanBackend> backend,
                 std::unique_ptr<Detector> detector)
    : config_(std::move(config)),
      clock_(clock),
      backend_(std::move(backend)),
      detector_(std::move(detector)),
      own_backend_(backend_ == nullptr),
      spool_(config_.spool),
      dds_(config_.dds) {
  std::string why;
  if (!spool_.open(&why)) throw std::runtime_error(why);
  spool_.set_picture(picture_writer(config_.objects));
  if (own_backend_) {
    backend_ = std::make_unique<DeviceBackend>(config_);
    detector_ = std::make_unique<ModelDetector>(config_);
  }
  dds_.publish_frames(config_);
  build_pipeline();
}

Service::~Service() { pipeline_->stop(true); }

void Service::build_pipeline() {
  PipelineOptions options;
  options.queue_capacity = config_.service.queue_capacity;
  options.scan_timeout = seconds(config_.service.scan_timeout_s);
  options.detect_timeout = seconds(config_.detection.timeout_s);
  pipeline_ = std::make_unique<Pipeline>(options, *backend_, *detector_, &spool_, board_, clock_);
}

std::optional<DetectionResult> Service::admit(ScanRequest req, const std::string& decode_error) {
  std::optional<DetectionResult> refused;
  {
    std::lock_guard lock(mutex_);
    const std::string why = decode_error.empty() ? validate_request(req, config_) : decode_error;
    if (!why.empty()) {
      spdlog::warn("request \"{}\" rejected: {}", log_escape(req.id), log_escape(why));
      refused = DetectionResult::error(req, "bad request: " + why);
    } else {
      refused = submit_locked(req);
    }
  }
  if (refused) board_.on_result(*refused);
  return refused;
}

std::optional<DetectionResult> Service::submit_locked(const ScanRequest& req) {
  switch (pipeline_->submit(req)) {
    case Submit::kAccepted:
      spdlog::info("request {} ({}) queued", log_escape(req.id), to_string(req.kind));
      return std::nullopt;
    case Submit::kBusy:
      spdlog::warn("request {} refused: busy", log_escape(req.id));
      return DetectionResult::error(
          req, fmt::format("busy: {} requests queued", pipeline_->queue_depth()));
    case Submit::kStopping:
      return DetectionResult::error(req, "daemon stopping");
  }
  return DetectionResult::error(req, "daemon stopping");
}

PipelineSnapshot Service::snapshot() const {
  std::lock_guard lock(mutex_);
  return {pipeline_->state(),         pipeline_->queue_depth(), pipeline_->completed(),
          pipeline_->rejected_busy(), pipeline_->last_error(),  stalled()};
}

std::optional<ObjectModel> Service::model(const std::string& name) const {
  std::lock_guard lock(mutex_);
  const ObjectModelConfig* o = config_.object(name);
  return o ? std::optional<ObjectModel>(o->model) : std::nullopt;
}

std::filesystem::path Service::spool_directory() const {
  std::lock_guard lock(mutex_);
  return config_.spool.directory;
}

DaemonConfig Service::config_copy() const {
  std::lock_guard lock(mutex_);
  return config_;
}

void Service::step(std::chrono::milliseconds timeout) {
  apply_pending_reload();
  dds_.poll_requests(
      timeout, [&](ScanRequest req, const std::string& error) { admit(std::move(req), error); });
  // A device or the pipeline changing state is published at once, not only every period: an
  // outage shorter than the period (an axis whose Modbus server drops and is back within a
  // second) would otherwise never reach rt/diagnostics.
  const PipelineSnapshot snap = snapshot();
  std::vector<NamedHealth> health = backend_->health();
  std::vector<int> states = states_of(snap, health);
  if (clock_.now() < next_diagnostics_ && states == published_states_) return;
  auto statuses = diagnostics_.build(health, snap, clock_.now());
  board_.set_diagnostics(statuses);
  dds_.publish_diagnostics(std::move(statuses));
  published_states_ = std::move(states);
  next_diagnostics_ = clock_.now() + seconds(config_.dds.diagnostics_period_s);
}

bool Service::stalled() const {
  return pipeline_->stalled(clock_.now(), seconds(config_.service.stall_timeout_s));
}

std::string Service::status_line() const {
  return fmt::format(
      "{}; queue {}; {} scans done{}", to_string(pipeline_->state()), pipeline_->queue_depth(),
      pipeline_->completed(),
      pipeline_->last_error().empty() ? "" : "; last error: " + pipeline_->last_error());
}

bool Service::reload(const DaemonConfig& next, std::string* why) {
  if (next.dds.domain_id != config_.dds.domain_id ||
      next.dds.config_uri != config_.dds.config_uri || next.dds.security != config_.dds.security ||
      next.dds.cloud_depth != config_.dds.cloud_depth ||
      next.dds.request_depth != config_.dds.request_depth ||
      next.dds.partition != config_.dds.partition ||
      next.dds.ros_namespace != config_.dds.ros_namespace) {
    *why = "dds settings changed; they apply on restart only (config not reloaded)";
    return false;
  }
  if (next.http != config_.http || next.tcp != config_.tcp) {
    *why = "http or tcp settings changed; they apply on restart only (config not reloaded)";
    return false;
  }
  Spool spool(next.spool);
  if (!spool.open(why)) return false;
  spool.set_picture(picture_writer(next.objects));
  // Devices first (a simulated scene may fail to load): a refused config changes nothing.
  std::unique_ptr<ScanBackend> backend;
  if (own_backend_) {
    try {
      backend = std::make_unique<DeviceBackend>(next);
    } catch (const std::exception& e) {
      *why = e.what();
      return false;
    }
  }
  // The running scan finishes with the old configuration; step() swaps the new one in as soon
  // as the pipeline is between scans (at once when it is idle), and requests go on being taken.
  {
    std::lock_guard lock(mutex_);
    pending_ =
        std::make_unique<PendingReload>(PendingReload{next, std::move(spool), std::move(backend)});
    pipeline_->hold();
  }
  apply_pending_reload();
  if (reload_pending()) spdlog::info("new configuration waits for the running scan to finish");
  return true;
}

void Service::apply_pending_reload() {
  std::vector<DetectionResult> refused;
  {
    std::lock_guard lock(mutex_);
    if (!pending_ || !pipeline_->idle()) return;
    std::deque<ScanRequest> waiting = pipeline_->take_queue();
    pipeline_->stop(false);  // between scans and nothing queued: returns at once
    pipeline_.reset();
    config_ = std::move(pending_->config);
    spool_ = std::move(pending_->spool);
    if (own_backend_) {
      backend_ = std::move(pending_->backend);
      detector_ = std::make_unique<ModelDetector>(config_);
    }
    pending_.reset();
    dds_.publish_frames(config_);
    build_pipeline();
    for (auto& request : waiting) {
      if (auto r = submit_locked(request)) refused.push_back(std::move(*r));
    }
  }
  for (const auto& r : refused) board_.on_result(r);
}

}  // namespace rangefit::daemon
