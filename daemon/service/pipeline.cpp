#include "daemon/service/pipeline.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <future>

#include "daemon/service/log_escape.hpp"

namespace rangefit::daemon {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Pipeline::Pipeline(PipelineOptions options, ScanBackend& backend, Detector& detector, Spool* spool,
                   ResultSink& sink, hal::Clock& clock)
    : options_(options),
      backend_(backend),
      detector_(detector),
      spool_(spool),
      sink_(sink),
      clock_(clock) {
  touch();
  set_state(LifecycleState::kIdle, "", "");
  worker_ = std::thread([this] { run(); });
}

Pipeline::~Pipeline() { stop(true); }

Submit Pipeline::submit(ScanRequest request) {
  std::size_t depth = 0;
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return Submit::kStopping;
    if (queue_.size() >= options_.queue_capacity) {
      ++busy_;
      return Submit::kBusy;
    }
    queue_.push_back(std::move(request));
    depth = queue_.size();
  }
  spdlog::debug("request queued, depth {}", depth);
  cv_.notify_one();
  return Submit::kAccepted;
}

void Pipeline::stop(bool abort) {
  std::deque<ScanRequest> dropped;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    dropped.swap(queue_);
  }
  if (abort) cancel_ = true;
  cv_.notify_all();
  for (const auto& r : dropped) sink_.on_result(DetectionResult::error(r, "daemon stopping"));
  if (worker_.joinable()) worker_.join();
}

std::size_t Pipeline::queue_depth() const {
  std::lock_guard lock(mutex_);
  return queue_.size();
}

std::string Pipeline::last_error() const {
  std::lock_guard lock(mutex_);
  return last_error_;
}

void Pipeline::set_options(PipelineOptions options) {
  std::lock_guard lock(mutex_);
  options_ = options;
}

void Pipeline::hold() {
  std::lock_guard lock(mutex_);
  held_ = true;
}

bool Pipeline::idle() const {
  std::lock_guard lock(mutex_);
  return held_ && !processing_;
}

std::deque<ScanRequest> Pipeline::take_queue() {
  std::deque<ScanRequest> taken;
  std::lock_guard lock(mutex_);
  taken.swap(queue_);
  return taken;
}

void Pipeline::set_state(LifecycleState s, const std::string& detail, const std::string& active) {
  state_ = s;
  sink_.on_state(s, detail, active, queue_depth());
}

void Pipeline::run() {
  for (;;) {
    ScanRequest request;
    {
      std::unique_lock lock(mutex_);
      // Waking every 100 ms is the idle heartbeat the watchdog looks for.
      cv_.wait_for(lock, std::chrono::milliseconds(100),
                   [&] { return stopping_ || (!held_ && !queue_.empty()); });
      touch();
      if (stopping_) return;
      if (held_ || queue_.empty()) continue;
      request = std::move(queue_.front());
      queue_.pop_front();
      processing_ = true;
    }
    process(request);
    touch();
    std::lock_guard lock(mutex_);
    processing_ = false;
  }
}

// The backend sees one cancel flag: set when the pipeline aborts or the scan deadline passes.
// A small timer thread per scan sets it; scans last seconds, so the thread costs nothing.
ScanOutcome Pipeline::run_scan(const ScanRequest& request, bool* timed_out) {
  std::atomic<bool> cancel{false};
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  hal::Duration limit;
  {
    std::lock_guard lock(mutex_);
    limit = options_.scan_timeout;
  }
  std::thread timer([&] {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    std::unique_lock lock(m);
    while (!done) {
      cv.wait_for(lock, std::chrono::milliseconds(20));
      if (cancel_) cancel = true;
      if (limit > hal::Duration::zero() && std::chrono::steady_clock::now() >= deadline && !done &&
          !cancel) {
        *timed_out = true;
        cancel = true;
      }
    }
  });
  ScanOutcome outcome;
  try {
    outcome = backend_.scan(request, cancel, [this] { touch(); });
  } catch (const std::exception& e) {
    outcome.status = hal::Status::Error(std::string("scan threw: ") + e.what());
  }
  {
    std::lock_guard lock(m);
    done = true;
  }
  cv.notify_all();
  timer.join();
  if (*timed_out) {
    outcome.status = hal::Status::Error(
        fmt::format("scan timeout: not complete after {:.1f} s (service.scan_timeout_s)",
                    std::chrono::duration<double>(limit).count()));
    outcome.cloud = {};
  }
  return outcome;
}

DetectionResult Pipeline::run_detection(const ScanOutcome& scan, const ScanRequest& request) {
  hal::Duration limit;
  {
    std::lock_guard lock(mutex_);
    limit = options_.detect_timeout;
  }
  auto detect = [this, &scan, &request] {
    try {
      return detector_.detect(scan.cloud, request, scan.sensor, scan.views);
    } catch (const std::exception& e) {
      return DetectionResult::error(request, std::string("detector threw: ") + e.what());
    }
  };
  if (limit <= hal::Duration::zero()) return detect();
  auto future = std::async(std::launch::async, detect);
  if (future.wait_for(limit) == std::future_status::ready) return future.get();
  // Answered now; the detector's thread is joined before the next request (pending_detection_).
  pending_detection_ = std::move(future);
  return DetectionResult::error(
      request, fmt::format("detection timeout: no result after {:.1f} s (detection.timeout_s)",
                           std::chrono::duration<double>(limit).count()));
}

void Pipeline::process(const ScanRequest& request) {
  set_state(LifecycleState::kScanning, "", request.id);
  const auto t0 = std::chrono::steady_clock::now();
  bool scan_timed_out = false;
  ScanOutcome outcome = run_scan(request, &scan_timed_out);
  DetectionResult result;
  const double scan_s = seconds_since(t0);
  bool failed = !outcome.status;
  if (outcome.status) {
    set_state(LifecycleState::kDetecting, "", request.id);
    const auto t1 = std::chrono::steady_clock::now();
    result = run_detection(outcome, request);
    result.detect_seconds = seconds_since(t1);
    failed = pending_detection_.valid();
  } else if (scan_timed_out) {
    result = DetectionResult::error(request, outcome.status.message);
  } else {
    result = DetectionResult::error(request, "scan failed: " + outcome.status.message);
  }
  result.request_id = request.id;
  result.kind = request.kind;
  result.model = request.model;
  result.num_points = outcome.cloud.size();
  result.scan_seconds = scan_s;
  result.acquired_wall_ns = outcome.acquired_wall_ns;
  touch();

  if (spool_ != nullptr) {
    std::string why;
    if (!spool_->write(request, outcome.cloud, result, &why)) {
      spdlog::error("{}", why);
      if (result.reason.empty()) result.reason = "not spooled: " + why;
    }
  }
  // State first, then the result: a client holding the result sees the settled state.
  if (!failed) {
    spdlog::info("request {}: {} ({} points, scan {:.2f} s, detect {:.2f} s){}",
                 log_escape(request.id), result.found ? "found" : "not found", result.num_points,
                 result.scan_seconds, result.detect_seconds,
                 result.reason.empty() ? "" : ": " + result.reason);
    set_state(LifecycleState::kIdle, "", "");
  } else {
    {
      std::lock_guard lock(mutex_);
      last_error_ = result.reason;
    }
    spdlog::error("request {}: {}", log_escape(request.id), log_escape(result.reason));
    // FAULT is reported while the failure is the latest news; the next good scan clears it.
    set_state(LifecycleState::kFault, result.reason, "");
  }
  if (!outcome.cloud.empty()) sink_.on_cloud(request, outcome.cloud);
  ++completed_;
  sink_.on_result(result);
  if (pending_detection_.valid()) {
    spdlog::warn("request {}: waiting for the timed-out detector to return",
                 log_escape(request.id));
    pending_detection_.wait();  // no touch(): a detector that never returns starves the watchdog
    pending_detection_ = {};
  }
}

}  // namespace rangefit::daemon
