#pragma once
// Internal seams for daemon tests: a scan backend whose device can be unplugged, a detector
// that reports the cloud's centroid, a recording sink and a clock the test advances by hand.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

#include "daemon/service/pipeline.hpp"

namespace rangefit::test {

// A request for the CSS with the given id, as the pipeline tests submit them.
inline daemon::ScanRequest request(const std::string& id) {
  daemon::ScanRequest r;
  r.id = id;
  r.sensor = "css";
  return r;
}

inline PointCloud grid_cloud(int n) {
  PointCloud c;
  for (int i = 0; i < n; ++i) c.points.emplace_back(i % 10, (i / 10) % 10, 0.5 * i);
  return c;
}

class ManualClock final : public hal::Clock {
 public:
  hal::Timestamp now() const override { return hal::Timestamp(ns_.load()); }
  void sleep_until(hal::Timestamp) override {}
  void advance(hal::Duration d) { ns_ += d.count(); }

 private:
  std::atomic<std::int64_t> ns_{1'000'000'000};
};

class FakeBackend final : public daemon::ScanBackend {
 public:
  std::atomic<bool> present{true};
  std::atomic<bool> hang{false};  // scan() blocks without progress until cancelled or released
  std::atomic<bool> release{false};
  std::atomic<int> scans{0};
  int points = 100;

  daemon::ScanOutcome scan(const daemon::ScanRequest&, const std::atomic<bool>& cancel,
                           const std::function<void()>& progress) override {
    ++scans;
    while (hang && !cancel && !release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (cancel) return {hal::Status::Error("cancelled"), {}};
    if (!present) return {hal::Status::Error("css: device disappeared mid-scan"), {}};
    progress();
    return {hal::Status::Ok(), grid_cloud(points)};
  }
  std::vector<daemon::NamedHealth> health() const override {
    hal::DeviceHealth h;
    h.state = present ? hal::DeviceState::kReady : hal::DeviceState::kDisconnected;
    if (!present) h.message = "device disappeared";
    return {{"css", h}};
  }
};

class CentroidDetector final : public daemon::Detector {
 public:
  bool throw_next = false;
  daemon::DetectionResult detect(const PointCloud& cloud, const daemon::ScanRequest&,
                                 const daemon::ScanSensor&,
                                 std::span<const daemon::SensorScan>) override {
    if (throw_next) throw std::runtime_error("boom");
    daemon::DetectionResult r;
    if (cloud.empty()) {
      r.reason = "empty cloud";
      return r;
    }
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& p : cloud.points) c += p;
    daemon::PartPose part;
    part.name = "centroid";
    part.T_world_part.translation() = c / static_cast<double>(cloud.size());
    part.score = 1.0;
    r.parts.push_back(part);
    r.found = true;
    return r;
  }
};

class RecordingSink final : public daemon::ResultSink {
 public:
  void on_cloud(const daemon::ScanRequest&, const PointCloud& cloud) override {
    std::lock_guard lock(mutex_);
    clouds.push_back(cloud.size());
  }
  void on_result(const daemon::DetectionResult& r) override {
    {
      std::lock_guard lock(mutex_);
      results.push_back(r);
    }
    cv_.notify_all();
  }
  void on_state(daemon::LifecycleState s, const std::string&, const std::string&,
                std::size_t) override {
    std::lock_guard lock(mutex_);
    states.push_back(s);
  }
  // Waits (generously; not a timing assertion) until n results arrived.
  bool wait_results(std::size_t n) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, std::chrono::seconds(30), [&] { return results.size() >= n; });
  }
  std::vector<daemon::DetectionResult> results_copy() {
    std::lock_guard lock(mutex_);
    return results;
  }

  std::vector<std::size_t> clouds;
  std::vector<daemon::DetectionResult> results;
  std::vector<daemon::LifecycleState> states;

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
};

}  // namespace rangefit::test
