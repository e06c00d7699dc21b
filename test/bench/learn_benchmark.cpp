// Model learning time (detect/model_learning.hpp; goal: <= 200 ms per part) on the teach-in scans
// of the tests (test/detect/learn_scenes.hpp: one view, 0.05 mm noise, ~30,000 points), as a
// ratio to a baseline measured in the same run: the moment-started pose fit of the true model
// (detect/pose_fit.hpp, what the detector runs per refinement) on the same object points. The
// machine is shared, so absolute times are noisy; the ratio is the figure to compare.
#include <benchmark/benchmark.h>

#include <chrono>
#include <numeric>
#include <vector>

#include "detect/learn/learn_segment.hpp"
#include "detect/learn/model_learning.hpp"
#include "detect/object/pose_fit.hpp"
#include "sim/scene_objects.hpp"
#include "test/detect/learn_scenes.hpp"

namespace rangefit {
namespace {

Superquadric target(int which) {
  switch (which) {
    case 0:
      return sim::cylinder_model();
    case 1:
      return sim::box_model();
    case 2:
      return sim::sphere_model();
    case 3:
      return sim::cone_model();
    default:
      return test::random_superquadric(static_cast<std::uint64_t>(which));
  }
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// 0-3: cylinder, box, sphere, cone; 4, 5: random superquadrics (seeds 4, 5).
void BM_LearnOnePart(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const Superquadric truth = target(which);
  const std::vector<sim::ScenePart> parts = test::resting(truth, 3);
  const std::vector<Eigen::Vector3d> scan = test::teach_scan(parts, 1, 0.05, 3);
  // The baseline on the segmented object's points, timed by hand in this run.
  const SegmentResult seg = segment_object(scan);
  std::vector<Eigen::Vector3d> object;
  for (std::uint32_t i : seg.object) object.push_back(scan[i]);
  double baseline_ms = 0.0;
  constexpr int kBaselineRuns = 20;
  for (int k = 0; k < kBaselineRuns; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(fit_pose_from_moments(truth, object));
    baseline_ms += ms_since(t0) / kBaselineRuns;
  }
  double learn_ms = 0.0;
  int runs = 0;
  LearnResult r;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    r = learn_model(scan);
    learn_ms += ms_since(t0);
    ++runs;
    benchmark::DoNotOptimize(r);
  }
  learn_ms /= runs;
  state.counters["ms_per_part"] =
      learn_ms / static_cast<double>(std::max<std::size_t>(1, r.parts.size()));
  state.counters["pose_fit_ms"] = baseline_ms;
  state.counters["ratio_to_pose_fit"] = learn_ms / baseline_ms;
  state.counters["starts"] = r.starts;
  state.counters["object_points"] = static_cast<double>(seg.object.size());
}
BENCHMARK(BM_LearnOnePart)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->Iterations(5);

// The stages alone: segmentation (plane removal and clustering) of the same scan.
void BM_SegmentTeachScan(benchmark::State& state) {
  const std::vector<sim::ScenePart> parts = test::resting(sim::cylinder_model(), 3);
  const std::vector<Eigen::Vector3d> scan = test::teach_scan(parts, 1, 0.05, 3);
  for (auto _ : state) benchmark::DoNotOptimize(segment_object(scan));
}
BENCHMARK(BM_SegmentTeachScan)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rangefit

BENCHMARK_MAIN();
