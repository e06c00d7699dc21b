#pragma once
// rangefitd as a separate process on the simulated cell at full speed (sim.time_scale = 0, the
// CSS over the bore plate), for the tests that load it with requests (daemon_soak.cpp,
// many_clients.cpp): its configuration file, which can be rewritten for a SIGHUP, and the bore
// requests they send, with bad ones in a fixed rotation.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "daemon/service/scan_types.hpp"
#include "test/daemon/daemon_process.hpp"
#include "test/daemon/dds_test_env.hpp"

namespace rangefit::test {

// The kinds of request the load tests send, in a fixed rotation of ten: 7 bore scans, 3 bad.
enum class LoadKind { kBore, kBadRadius, kUnknownSensor, kUnknownModel };
inline LoadKind load_kind(std::size_t i) {
  switch (i % 10) {
    case 6:
      return LoadKind::kBadRadius;
    case 7:
      return LoadKind::kUnknownSensor;
    case 8:
      return LoadKind::kUnknownModel;
    default:
      return LoadKind::kBore;
  }
}
inline bool is_bad(std::size_t i) { return load_kind(i) != LoadKind::kBore; }

// Request i (id prefix + i): a short sweep over the 12 mm bore under the CSS (bore_plate.toml), a
// few thousand points, a found bore with its pose, cloud, spool entry and (when on) picture in a
// few milliseconds; or one of the bad requests of load_kind(i).
inline daemon::ScanRequest load_request(std::size_t i, const std::string& prefix) {
  daemon::ScanRequest r;
  r.id = prefix + std::to_string(i);
  r.kind = daemon::DetectKind::kBore;
  r.bore.position_mm = Eigen::Vector3d(0.8, -0.5, 285.8);
  r.bore.axis = Eigen::Vector3d::UnitZ();
  r.bore.radius_mm = 6.0;
  r.sweep_start = -0.05;  // rad
  r.sweep_end = 0.05;
  r.sweep_speed = 0.1;  // rad/s
  switch (load_kind(i)) {
    case LoadKind::kBore:
      break;
    case LoadKind::kBadRadius:
      r.bore.radius_mm = 0.0;
      break;
    case LoadKind::kUnknownSensor:
      r.sensor = "no_such_sensor";
      break;
    case LoadKind::kUnknownModel:
      r.kind = daemon::DetectKind::kObject;
      r.model = "no_such_model";
      break;
  }
  return r;
}

struct SimDaemonOptions {
  bool pictures = false;           // spool a picture.png per scan (cairo), as by default
  std::size_t queue_capacity = 4;  // small, so that a burst is answered "busy"
  std::vector<std::string> env{};  // "NAME=value" for the daemon (e.g. NOTIFY_SOCKET)
};

class SimDaemon {
 public:
  SimDaemon(const std::string& name, SimDaemonOptions options) : options_(std::move(options)) {
    namespace fs = std::filesystem;
    dir_ = fs::temp_directory_path() / ("rangefit_sim_daemon_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    domain_ = dds_test_domain();  // also points CYCLONEDDS_URI at the loopback config
    write_config(options_.queue_capacity);
    process_.emplace(RANGEFITD_PATH, dir_ / "rangefitd.toml", options_.env);
  }
  ~SimDaemon() {
    if (process_) process_->stop();
    std::filesystem::remove_all(dir_);
  }
  SimDaemon(const SimDaemon&) = delete;
  SimDaemon& operator=(const SimDaemon&) = delete;

  // Rewrites the configuration file (read again on SIGHUP): the same cell, DDS domain and spool,
  // another queue capacity. A small spool, so old entries are pruned all along as on a cell that
  // runs for weeks.
  void write_config(std::size_t queue_capacity) const {
    const std::string scenes = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/";
    std::ofstream(dir_ / "rangefitd.toml")
        << "[service]\nbore_sensor = \"css\"\nqueue_capacity = " << queue_capacity
        << "\nlog_level = \"warn\"\n"
        << "[dds]\ndomain_id = " << domain_ << "\ndiagnostics_period_s = 0.5\n"
        << "[spool]\ndirectory = \"" << (dir_ / "spool").string()
        << "\"\nmax_bytes = 8000000\npictures = " << (options_.pictures ? "true" : "false")
        << "\n[sim]\ntime_scale = 0\nseed = 3\n"
        << "[[devices]]\nname = \"css\"\nkind = \"css\"\ndriver = \"sim\"\nscene = \"" << scenes
        << "bore_plate.toml\"\n";
  }
  const std::filesystem::path& dir() const { return dir_; }
  std::uint32_t domain() const { return domain_; }
  pid_t pid() const { return process_->pid(); }
  void signal(int sig) const { process_->signal(sig); }
  int stop() {
    const int status = process_->stop();
    process_.reset();
    return status;
  }

 private:
  SimDaemonOptions options_;
  std::filesystem::path dir_;
  std::uint32_t domain_ = 0;
  std::optional<DaemonProcess> process_;
};

}  // namespace rangefit::test
