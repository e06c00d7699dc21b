// rangefitd benchmarks on loopback DDS (a reserved domain, loopback-only Cyclone config):
//   BM_CloudConvertOnly        baseline: building the PointCloud2 of 140,000 points
//   BM_PublishCloud140k        write + receive of that cloud through DDS (p50/p99 counters)
//   BM_BoreRequestToResult     DetectRequest → Detection through the service, replayed bore scan
//   BM_SimCssScanOnly          baseline: one full simulated CSS scan of the bore plate, fused,
//                              as fast as possible (daemon/sim_cell, no detection, no DDS)
//   BM_SimCssBoreRequestToResult  DetectRequest → Detection with that scan + bore detection +
//                              spool + cloud publication through the service (driver = "sim")
// Counters: p50_ms, p99_ms per run and rss_mb of the process after the run (steady state).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "daemon/cell/sim_cell.hpp"
#include "daemon/dds/client.hpp"
#include "daemon/rangefitd/service.hpp"
#include "io/ply.hpp"
#include "test/daemon/dds_test_env.hpp"
#include "test/support/synthetic_bore.hpp"

namespace {
using namespace rangefit;
using Clock = std::chrono::steady_clock;

std::uint32_t domain() { return test::dds_test_domain(); }

double rss_mb() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      double kb = 0;
      in >> kb;
      return kb / 1024.0;
    }
  }
  return 0;
}

void percentiles(benchmark::State& state, std::vector<double> ms) {
  if (ms.empty()) return;
  std::sort(ms.begin(), ms.end());
  state.counters["p50_ms"] = ms[ms.size() / 2];
  state.counters["p99_ms"] = ms[std::min(ms.size() - 1, ms.size() * 99 / 100)];
  state.counters["rss_mb"] = rss_mb();
}

PointCloud cloud140k() {
  PointCloud c;
  for (int i = 0; i < 140000; ++i) c.points.emplace_back(i % 400, (i / 400) % 350, 0.01 * i);
  return c;
}

void BM_CloudConvertOnly(benchmark::State& state) {
  const PointCloud cloud = cloud140k();
  std::vector<double> ms;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    daemon::CloudOut out(cloud);
    benchmark::DoNotOptimize(out.msg().data._buffer);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  percentiles(state, ms);
}
BENCHMARK(BM_CloudConvertOnly)->Unit(benchmark::kMillisecond)->Iterations(30);

void BM_PublishCloud140k(benchmark::State& state) {
  const PointCloud cloud = cloud140k();
  dds::Participant pub(domain());
  dds::Writer<sensor_msgs_msg_dds__PointCloud2_> writer(pub, daemon::topics::kCloud,
                                                        &sensor_msgs_msg_dds__PointCloud2__desc,
                                                        daemon::topics::cloud_qos());
  daemon::DdsClient client(domain());
  while (writer.matched() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::vector<double> ms;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    daemon::CloudOut out(cloud);
    writer.write(out.msg());
    std::size_t got = 0;
    while (got != cloud.size()) {
      client.poll(std::chrono::milliseconds(5),
                  {.cloud = [&](const PointCloud& c) { got = c.size(); }});
    }
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  percentiles(state, ms);
}
BENCHMARK(BM_PublishCloud140k)->Unit(benchmark::kMillisecond)->Iterations(30);

// Runs rangefitd's service loop on `config` and times bore requests for `bore` from a separate
// DDS client, request to result, until the benchmark stops; p50/p99 go into the counters.
void time_bore_requests(benchmark::State& state, const daemon::DaemonConfig& config, char prefix,
                        const daemon::BorePrior& bore) {
  hal::MonotonicClock clock;
  daemon::Service service(config, clock);
  std::atomic<bool> running{true};
  std::thread loop([&] {
    while (running) service.step(std::chrono::milliseconds(5));
  });
  daemon::DdsClient client(domain());
  client.wait_for_daemon(std::chrono::seconds(20));
  std::vector<double> ms;
  int n = 0;
  for (auto _ : state) {
    daemon::ScanRequest req;
    req.id = std::to_string(++n);
    req.id.insert(0, 1, prefix);  // not prefix + ...: GCC 12's false -Wrestrict (bug 105329)
    req.bore = bore;
    const auto t0 = Clock::now();
    client.send(req, false);
    auto r = client.wait_result(req.id, std::chrono::seconds(60));
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    if (!r || !r->found) state.SkipWithError("bore not found");
  }
  running = false;
  loop.join();
  percentiles(state, ms);
}

void BM_BoreRequestToResult(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / "rangefit_daemon_benchmark";
  std::filesystem::create_directories(dir);
  sim::SyntheticBoreOptions opt;
  const auto scan = sim::make_synthetic_bore(opt);
  io::write_ply(dir / "plate.ply", scan.cloud);
  daemon::DaemonConfig config;
  config.dds.domain_id = domain();
  config.spool.directory = dir / "spool";
  config.service.bore_sensor = "css";
  daemon::DeviceConfig css;
  css.name = css.kind = "css";
  css.driver = daemon::DriverKind::kReplay;
  css.replay_file = dir / "plate.ply";
  config.devices.push_back(css);
  daemon::BorePrior bore;
  bore.position_mm = scan.truth.entrance;
  bore.axis = scan.truth.axis;
  bore.radius_mm = opt.radius;
  time_bore_requests(state, config, 'b', bore);
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_BoreRequestToResult)->Unit(benchmark::kMillisecond)->Iterations(10);

daemon::DaemonConfig sim_css_config(const std::filesystem::path& dir) {
  daemon::DaemonConfig config;
  config.dds.domain_id = domain();
  config.spool.directory = dir / "spool";
  config.service.bore_sensor = "css";
  config.sim.time_scale = 0.0;  // as fast as possible
  daemon::DeviceConfig css;
  css.name = css.kind = "css";
  css.driver = daemon::DriverKind::kSim;
  css.scene = std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/bore_plate.toml";
  config.devices.push_back(css);
  return config;
}

void BM_SimCssScanOnly(benchmark::State& state) {
  const auto config = sim_css_config(std::filesystem::temp_directory_path());
  daemon::SimCell cell(config);
  daemon::ScanRequest req;
  req.id = "scan";
  std::atomic<bool> cancel{false};
  std::vector<double> ms;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const auto out = cell.scan(config.devices[0], req, cancel, [] {});
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    if (!out.status) state.SkipWithError(out.status.message.c_str());
    points = out.cloud.size();
  }
  percentiles(state, ms);
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_SimCssScanOnly)->Unit(benchmark::kMillisecond)->Iterations(10);

void BM_SimCssBoreRequestToResult(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / "rangefit_daemon_benchmark_sim";
  std::filesystem::create_directories(dir);
  daemon::BorePrior bore;
  bore.position_mm = Eigen::Vector3d(0.8, -0.5, 285.8);  // 12 mm bore at (0, 0, 285.8)
  bore.axis = Eigen::Vector3d::UnitZ();
  bore.radius_mm = 6.0;
  time_bore_requests(state, sim_css_config(dir), 's', bore);
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_SimCssBoreRequestToResult)->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace

BENCHMARK_MAIN();
