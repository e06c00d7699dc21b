// Fusion speed: a full CSS scan (25 s at 7 Hz, > 75,000 points) and the latency of one
// revolution (last sample in -> world points out), each against a naive baseline measured in
// the same run: per point, a binary search in the joint stream and CssGeometry's full
// T_world_css(omega) * sensor_point(angle, range), into an unreserved cloud. Ratios are printed
// after the table; all figures are medians of per-iteration thread CPU time.
//
//   build-*/test/bench/fusion_benchmark --benchmark_min_time=0.5

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>
#include <string>
#include <vector>

#include "fusion/css_assembler.hpp"
#include "test/fusion/css_truth.hpp"

namespace rangefit::fusion {
namespace {

constexpr int kRevolutions = 175;  // 2 * delta * R / v = 25 s at 7 Hz (thesis 4.2.1)
constexpr int kCols = hal::CssRevolution::kSamples;

const testing::CssTruthScan& full_scan() {
  static const testing::CssTruthScan scan = [] {
    testing::CssTruthOptions o;
    o.revolutions = kRevolutions;
    o.joint_period = std::chrono::milliseconds(1);  // a 1 kHz CiA 402 SYNC joint stream
    return testing::make_css_truth(CssFusionConfig{}, o);
  }();
  return scan;
}

std::map<std::string, double>& results() {  // name -> seconds per iteration (median)
  static std::map<std::string, double> r;
  return r;
}

// CPU time of this thread: the machine is shared, and the targets are "on one core", so time
// spent preempted must not count (wall time is in Google Benchmark's own column).
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The baseline: one revolution, point by point, the obvious way.
void naive_fuse_revolution(const hal::CssGeometry& g, const hal::CssRevolution& rev,
                           const std::vector<hal::JointSample>& joints, PointCloud& cloud) {
  for (int i = 0; i < kCols; ++i) {
    const double r = rev.range_mm[i];
    if (!(r >= g.min_range_mm && r <= g.max_range_mm)) continue;
    const hal::Timestamp t = rev.stamp + rev.period * i / kCols;
    auto it =
        std::upper_bound(joints.begin(), joints.end(), t,
                         [](hal::Timestamp v, const hal::JointSample& j) { return v < j.stamp; });
    it = std::clamp(it, joints.begin() + 1, joints.end() - 1);
    const hal::JointSample& a = *(it - 1);
    const hal::JointSample& b = *it;
    const double f = static_cast<double>((t - a.stamp).count()) /
                     static_cast<double>((b.stamp - a.stamp).count());
    const double omega = a.angle_rad + f * (b.angle_rad - a.angle_rad);
    cloud.points.push_back(g.T_world_css(omega) * g.sensor_point(g.beam_angle(i, kCols), r));
    cloud.stamps.push_back(t);
  }
}

void BM_CssFullScan(benchmark::State& state) {
  const auto& scan = full_scan();
  CssAssembler assembler{CssFusionConfig{}};
  std::vector<double> times;
  std::size_t points = 0;
  for (auto _ : state) {
    const double t0 = thread_seconds();
    assembler.begin_scan();
    for (const auto& j : scan.joints) assembler.add_joint(j);
    for (const auto& r : scan.revolutions) assembler.add_revolution(r);
    FusedScan out = assembler.finish();
    benchmark::DoNotOptimize(out.cloud.points.data());
    times.push_back(thread_seconds() - t0);
    points = out.cloud.size();
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["median_ms"] = median(times) * 1e3;
  results()["full_scan"] = median(times);
}
BENCHMARK(BM_CssFullScan)->Unit(benchmark::kMillisecond);

void BM_CssFullScanNaive(benchmark::State& state) {
  const auto& scan = full_scan();
  const hal::CssGeometry g;
  std::vector<double> times;
  for (auto _ : state) {
    const double t0 = thread_seconds();
    PointCloud cloud;
    for (const auto& r : scan.revolutions) naive_fuse_revolution(g, r, scan.joints, cloud);
    benchmark::DoNotOptimize(cloud.points.data());
    times.push_back(thread_seconds() - t0);
  }
  state.counters["median_ms"] = median(times) * 1e3;
  results()["full_scan_naive"] = median(times);
}
BENCHMARK(BM_CssFullScanNaive)->Unit(benchmark::kMillisecond);

// One revolution arrives while the joint stream already covers it (the usual order): the time
// add_revolution() takes until its world points are in the cloud.
void BM_CssRevolutionLatency(benchmark::State& state) {
  const auto& scan = full_scan();
  CssAssembler assembler{CssFusionConfig{}};
  std::vector<double> times;
  std::size_t next = kRevolutions;
  for (auto _ : state) {
    if (next == kRevolutions) {  // start a new scan, outside the measured section
      state.PauseTiming();
      assembler.finish();
      assembler.begin_scan();
      for (const auto& j : scan.joints) assembler.add_joint(j);
      next = 0;
      state.ResumeTiming();
    }
    const double t0 = thread_seconds();
    benchmark::DoNotOptimize(assembler.add_revolution(scan.revolutions[next++]));
    times.push_back(thread_seconds() - t0);
  }
  state.counters["median_us"] = median(times) * 1e6;
  results()["revolution"] = median(times);
}
BENCHMARK(BM_CssRevolutionLatency)->Unit(benchmark::kMicrosecond);

void BM_CssRevolutionLatencyNaive(benchmark::State& state) {
  const auto& scan = full_scan();
  const hal::CssGeometry g;
  PointCloud cloud;
  std::vector<double> times;
  std::size_t next = 0;
  for (auto _ : state) {
    if (next == kRevolutions) {
      next = 0;
      cloud = PointCloud{};
    }
    const double t0 = thread_seconds();
    naive_fuse_revolution(g, scan.revolutions[next++], scan.joints, cloud);
    benchmark::DoNotOptimize(cloud.points.data());
    times.push_back(thread_seconds() - t0);
  }
  state.counters["median_us"] = median(times) * 1e6;
  results()["revolution_naive"] = median(times);
}
BENCHMARK(BM_CssRevolutionLatencyNaive)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rangefit::fusion

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  auto& r = rangefit::fusion::results();
  if (r.count("full_scan") && r.count("full_scan_naive")) {
    std::printf("full CSS scan: %.3f ms (target <= 2 ms), naive %.3f ms, naive/fusion = %.1fx\n",
                r["full_scan"] * 1e3, r["full_scan_naive"] * 1e3,
                r["full_scan_naive"] / r["full_scan"]);
  }
  if (r.count("revolution") && r.count("revolution_naive")) {
    std::printf(
        "revolution latency (median): %.2f us (target <= 50 us), naive %.2f us, naive/fusion = "
        "%.1fx\n",
        r["revolution"] * 1e6, r["revolution_naive"] * 1e6,
        r["revolution_naive"] / r["revolution"]);
  }
  return 0;
}
