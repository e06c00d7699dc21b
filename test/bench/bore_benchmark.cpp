// Bore detection speed. BM_Css, --css_table and --css_accuracy: the hardest realistic input,
// scans at the CSS's real density with double coverage (bench::css_bore_cases: a 4 mm blind
// bore whose few wall points a budget must not lose, 12 mm, 25 mm with a 55,000-point region,
// 50 mm seen through a strip, whose narrow arc leaves radius and offset barely determined, and
// d50_60k, the same at 0.15 mm with a ~60,000-point region: the hardest realistic case),
// 60k-94k points per scan: where a pipeline whose cost follows the point count is slowest. The
// default pipeline (region read at a stride within BoreOptions::region_budget, refinement
// polished on the full-resolution band) against, in the same run, the pipeline before the
// region budget ('full': every region point read, one-step refinement; its results are those of
// that pipeline) and session 1's (cost_bounded = false). The table prints median and worst
// thread-CPU time per case, the speed-ups, the stage times and the errors against the truth;
// --css_accuracy=N the median and worst entrance, axis and radius errors of the three
// pipelines over N held-out seeds (1001...):
//   taskset -c 0 build/test/bench/bore_benchmark --benchmark_filter=BM_Css --css_table=40
//   taskset -c 0 build/test/bench/bore_benchmark --benchmark_filter=NONE --css_accuracy=10
// --axis_bound=N: per case, the axis error over tuning and held-out seeds against the bound the
// fit's own covariance gives (BoreResult::sigma_axis):
//   build/test/bench/bore_benchmark --benchmark_filter=NONE --axis_bound=30
// --css_entrance=N: per case, the entrance error over tuning and held-out seeds split into the
// plane's part (height) and the axis's offset across itself, beside the fit's sigma_offset:
//   build/test/bench/bore_benchmark --benchmark_filter=NONE --css_entrance=20
// --thesis_tables=N: the thesis's tables 4.1-4.4 (RSF samples vs accuracy, RSF vs LSF circle
// per resolution, pipeline time per resolution) beside its figures (bore_thesis_tables.hpp).
// The rest: a ~75,000-point scan with a ~7,500-point region (5 mm bore, 0.2 mm spacing): the
// whole pipeline, the RSF step and the LSF baselines in one run, each with its accuracy against
// the ground truth as counters (axis_deg, radius_mm, entrance_mm); the session-1 k-d tree
// normals as the in-run baseline of the binned normals; the thesis's steepest-descent LSF both
// at its 200 iterations and at the iterations it needs to match the RSF's accuracy
// (BM_LsfSteepestToRsfAccuracy), the in-run baselines of BM_Rsf.
// BM_Shape, --shape_table=N and --shape_accuracy=N [--held_out]: cone and elliptic bores beside
// their cylinder twins (test/bench/bore_shape_bench.hpp):
//   taskset -c 0 build/test/bench/bore_benchmark --benchmark_filter=NONE --shape_table=20
//   build/test/bench/bore_benchmark --benchmark_filter=NONE --shape_accuracy=20 --held_out
//   taskset -c 0 build/test/bench/bore_benchmark --benchmark_repetitions=20
//       (add --benchmark_report_aggregates_only=true for the medians alone)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <numbers>

#include "detect/bore/bore_detector.hpp"
#include "detect/bore/cylinder_lsf.hpp"
#include "detect/bore/cylinder_rsf.hpp"
#include "detect/common/kdtree.hpp"
#include "detect/common/normals.hpp"
#include "detect/common/pca.hpp"
#include "test/bench/bore_bench_scan.hpp"
#include "test/bench/bore_shape_bench.hpp"
#include "test/bench/bore_thesis_tables.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit {
namespace {

struct Fixture {
  sim::SyntheticBoreScan scan;
  BorePrior prior;
  std::vector<Eigen::Vector3d> wall, wall_normals;  // segmented wall of the region
};

const Fixture& fixture(bool organised) {
  static Fixture f[2];
  Fixture& x = f[organised ? 1 : 0];
  if (!x.scan.cloud.empty()) return x;
  bench::BoreBenchScan b = bench::make_bore_bench_scan(organised);
  x.scan = std::move(b.scan);
  x.prior = b.prior;
  const auto& t = x.scan.truth;
  // The wall as the pipeline segments it (eq. 4.4-4.6), for the RSF and LSF benchmarks.
  std::vector<std::uint32_t> roi;
  for (std::uint32_t i = 0; i < x.scan.cloud.size(); ++i) {
    if ((x.scan.cloud.points[i] - t.entrance).norm() < 10.0) roi.push_back(i);
  }
  const KdTree tree(x.scan.cloud.points);
  NormalOptions no;
  no.view_dir = t.view_dir;
  const NormalEstimate ne = estimate_normals(x.scan.cloud.points, tree, roi, no);
  for (std::size_t i = 0; i < roi.size(); ++i) {
    const Eigen::Vector3d& n = ne.normals[i];
    if (n.isZero() || std::abs(n.dot(x.prior.axis)) > std::sin(5.0 * std::numbers::pi / 180)) {
      continue;
    }
    x.wall.push_back(x.scan.cloud.points[roi[i]]);
    x.wall_normals.push_back(n);
  }
  return x;
}

void accuracy(benchmark::State& state, const Eigen::Vector3d& axis, double radius) {
  const auto& t = fixture(false).scan.truth;
  state.counters["axis_deg"] =
      std::acos(std::min(1.0, std::abs(axis.normalized().dot(t.axis)))) * 180.0 / std::numbers::pi;
  state.counters["radius_mm"] = radius - t.radius;
}

void run_pipeline(benchmark::State& state, bool organised, double keep,
                  bool refine_all_region_points = true) {
  const Fixture& f = fixture(organised);
  BoreOptions opt;
  opt.view_dir = f.scan.truth.view_dir;
  opt.normal_keep = keep;
  opt.refine_all_region_points = refine_all_region_points;
  BoreResult r;
  for (auto _ : state) {
    r = detect_bore(f.scan.cloud, f.prior, opt);
    benchmark::DoNotOptimize(r);
  }
  accuracy(state, r.axis, r.radius);
  state.counters["entrance_mm"] = (r.entrance - f.scan.truth.entrance).norm();
  state.counters["points"] = static_cast<double>(r.counts.input);
  state.counters["roi"] = static_cast<double>(r.counts.roi);
  state.counters["wall"] = static_cast<double>(r.counts.wall);
  state.counters["normals_ms"] = r.time_ms.normals;
  state.counters["refine_ms"] = r.time_ms.refine;
  state.counters["refine_pts"] = static_cast<double>(r.counts.refine_inliers);
}

void BM_Pipeline(benchmark::State& s) { run_pipeline(s, false, 1.0); }
void BM_PipelineKeep20(benchmark::State& s) { run_pipeline(s, false, 0.2); }
// In-run baseline of the refinement: session 1's final fit on the segmented wall points only.
void BM_PipelineWallOnlyRefine(benchmark::State& s) { run_pipeline(s, false, 1.0, false); }
void BM_PipelineOrganised(benchmark::State& s) { run_pipeline(s, true, 1.0); }
void BM_PipelineOrganisedKeep20(benchmark::State& s) { run_pipeline(s, true, 0.2); }

// Normals of every region point (R = 2 mm, neighbours from the region plus an R margin): the
// k-d tree baseline of session 1 against the binned grid the pipeline uses, in the same run.
void run_normals(benchmark::State& state, bool binned) {
  const Fixture& f = fixture(false);
  std::vector<Eigen::Vector3d> pool;
  std::vector<std::uint32_t> queries;
  bench::region_normal_inputs(f.scan.cloud.points, f.prior.entrance, pool, queries);
  NormalOptions no;
  no.view_dir = f.scan.truth.view_dir;
  NormalEstimate e;
  for (auto _ : state) {
    if (binned) {
      e = estimate_normals_binned(pool, queries, no);
    } else {
      const KdTree tree(pool);
      e = estimate_normals(pool, tree, queries, no);
    }
    benchmark::DoNotOptimize(e);
  }
  state.counters["queries"] = static_cast<double>(queries.size());
  state.counters["kept"] = static_cast<double>(e.kept);
}
void BM_NormalsKdTree(benchmark::State& s) { run_normals(s, false); }
void BM_NormalsBinned(benchmark::State& s) { run_normals(s, true); }

void BM_Rsf(benchmark::State& state) {
  const Fixture& f = fixture(false);
  RsfResult r;
  for (auto _ : state) {
    r = fit_cylinder_rsf(f.wall, f.wall_normals, f.prior.axis, f.prior.entrance, 5.0, {}, 1);
    benchmark::DoNotOptimize(r);
  }
  accuracy(state, r.cylinder.axis, r.cylinder.radius);
  state.counters["wall"] = static_cast<double>(f.wall.size());
}

void run_lsf(benchmark::State& state, LsfMethod method, int iterations, bool from_pca) {
  const Fixture& f = fixture(false);
  CylinderLsfOptions o;
  o.method = method;
  o.max_iterations = iterations;
  o.huber_delta = 0.0;  // plain least squares, as the thesis's baseline
  // The thesis runs steepest descent for a fixed number of iterations.
  if (method == LsfMethod::kSteepestDescent) o.tolerance = 0.0;
  const Cylinder start = from_pca ? cylinder_from_pca(f.wall, 5.0)
                                  : Cylinder{f.prior.entrance, f.prior.axis, f.prior.radius};
  CylinderLsfResult r;
  for (auto _ : state) {
    r = fit_cylinder_lsf(f.wall, start, o);
    benchmark::DoNotOptimize(r);
  }
  accuracy(state, r.cylinder.axis, r.cylinder.radius);
  state.counters["iterations"] = r.iterations;
}

// The thesis's "equal accuracy" comparison (4.2.4, fig. 4.35): the fewest steepest-descent
// iterations from the CAD pose whose axis and radius errors are both within the RSF's.
int iterations_to_rsf_accuracy() {
  const Fixture& f = fixture(false);
  const auto& t = f.scan.truth;
  const RsfResult rsf =
      fit_cylinder_rsf(f.wall, f.wall_normals, f.prior.axis, f.prior.entrance, 5.0, {}, 1);
  const auto axis_cos = [&](const Cylinder& c) {
    return std::abs(c.axis.normalized().dot(t.axis));
  };
  CylinderLsfOptions o;
  o.method = LsfMethod::kSteepestDescent;
  o.huber_delta = 0.0;
  o.tolerance = 0.0;
  const Cylinder start{f.prior.entrance, f.prior.axis, f.prior.radius};
  for (int k = 1; k <= 2000; k = k < 20 ? k + 1 : k + k / 10) {
    o.max_iterations = k;
    const Cylinder c = fit_cylinder_lsf(f.wall, start, o).cylinder;
    if (axis_cos(c) >= axis_cos(rsf.cylinder) &&
        std::abs(c.radius - t.radius) <= std::abs(rsf.cylinder.radius - t.radius)) {
      return k;
    }
  }
  return 2000;
}

void BM_LsfSteepestToRsfAccuracy(benchmark::State& s) {
  static const int k = iterations_to_rsf_accuracy();
  run_lsf(s, LsfMethod::kSteepestDescent, k, false);
}

void BM_LsfSteepestFromCad(benchmark::State& s) {
  run_lsf(s, LsfMethod::kSteepestDescent, 200, false);
}
void BM_LsfSteepestFromPca(benchmark::State& s) {
  run_lsf(s, LsfMethod::kSteepestDescent, 200, true);
}
void BM_LsfLevenbergMarquardtFromCad(benchmark::State& s) {
  run_lsf(s, LsfMethod::kLevenbergMarquardt, 100, false);
}

// The CSS-density cases of bench::css_bore_cases() (see there why they are the hardest
// realistic input): the whole pipeline per case in each CssMode (0 the default, 1 the pipeline
// before the region budget, 2 session 1's) with the accuracy counters. --css_table prints median,
// worst and the ratios per case after the run.
struct CssFixture {
  std::string name;
  sim::SyntheticBoreScan scan;
  BorePrior prior;
};

const std::vector<CssFixture>& css_fixtures() {
  static const std::vector<CssFixture> f = [] {
    std::vector<CssFixture> out;
    for (const auto& c : bench::css_bore_cases()) {
      CssFixture x{c.name, sim::make_synthetic_bore(c.scan), {}};
      x.prior = bench::css_prior(x.scan.truth);
      out.push_back(std::move(x));
    }
    return out;
  }();
  return f;
}

// The pipelines compared: the default (region read at a stride within its budget), the one
// before the region budget (every region point read, one-step refinement, 60-point normal
// patches, 0.5 mm plane margin: the same results as before), and session 1's
// (BoreOptions::cost_bounded = false).
// kWorkspace: the default pipeline with a workspace kept between calls (as rangefitd keeps one),
// allocating nothing after the first call.
enum class CssMode { kDefault, kFullRegion, kSession1, kWorkspace };

BoreResult css_run(const sim::SyntheticBoreScan& scan, const BorePrior& prior, CssMode mode,
                   BoreWorkspace* workspace = nullptr) {
  BoreOptions opt;
  opt.view_dir = scan.truth.view_dir;
  opt.cost_bounded = mode != CssMode::kSession1;
  if (mode == CssMode::kFullRegion) {  // the options before the region budget
    opt.region_budget = 0;
    opt.refine_full_resolution = false;
    opt.normal_neighbours = 60.0;
    opt.refine_plane_margin = 0.5;
  }
  if (workspace) return detect_bore(scan.cloud, prior, opt, *workspace);
  return detect_bore(scan.cloud, prior, opt);
}

void BM_Css(benchmark::State& state) {
  const CssFixture& f = css_fixtures()[static_cast<std::size_t>(state.range(0))];
  const auto mode = static_cast<CssMode>(state.range(1));
  const char* labels[] = {"", " full region", " session 1", " workspace"};
  state.SetLabel(f.name + labels[state.range(1)]);
  BoreResult r;
  BoreWorkspace ws;
  BoreWorkspace* kept = mode == CssMode::kWorkspace ? &ws : nullptr;
  for (auto _ : state) {
    r = css_run(f.scan, f.prior, mode, kept);
    benchmark::DoNotOptimize(r);
  }
  const auto& t = f.scan.truth;
  state.counters["found"] = r.found;
  state.counters["entrance_mm"] = (r.entrance - t.entrance).norm();
  state.counters["axis_deg"] =
      std::acos(std::min(1.0, std::abs(r.axis.dot(t.axis)))) * 180.0 / std::numbers::pi;
  state.counters["radius_mm"] = r.radius - t.radius;
  state.counters["points"] = static_cast<double>(r.counts.input);
  state.counters["roi"] = static_cast<double>(r.counts.roi);
  state.counters["queries"] = static_cast<double>(r.counts.normal_queries);
  state.counters["wall"] = static_cast<double>(r.counts.wall);
  state.counters["normals_ms"] = r.time_ms.normals;
  state.counters["refine_ms"] = r.time_ms.refine;
}
BENCHMARK(BM_Css)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->ComputeStatistics("max", [](const std::vector<double>& v) {
      return *std::max_element(v.begin(), v.end());
    });

BENCHMARK(bench::BM_Shape)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pipeline)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PipelineKeep20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PipelineWallOnlyRefine)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PipelineOrganised)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PipelineOrganisedKeep20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NormalsKdTree)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NormalsBinned)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Rsf)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LsfSteepestToRsfAccuracy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LsfSteepestFromCad)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LsfSteepestFromPca)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LsfLevenbergMarquardtFromCad)->Unit(benchmark::kMillisecond);

// Per CSS case: median and worst whole-pipeline time over `runs` calls of each pipeline, and the
// baseline's over the cost-bounded's (the speed-up).
// Thread CPU time, ms: the machine the figures come from may be shared, and wall time then
// measures the neighbours.
double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

// Per-stage medians of the runs' own (steady clock) stage times.
BoreTimes median_stages(std::vector<BoreTimes> v) {
  BoreTimes m;
  const auto med = [&](double BoreTimes::*f) {
    std::vector<double> x;
    for (const auto& t : v) x.push_back(t.*f);
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    m.*f = x[x.size() / 2];
  };
  for (auto f : {&BoreTimes::roi, &BoreTimes::normals, &BoreTimes::segmentation, &BoreTimes::rsf,
                 &BoreTimes::refine, &BoreTimes::entrance, &BoreTimes::total}) {
    med(f);
  }
  return m;
}

void css_table(int runs) {
  std::printf(
      "\nCSS density, whole pipeline, %d runs each (thread CPU ms; 'full': every region\n"
      "point, the pipeline before the region budget; 's1': session 1's; 'ws': the default with\n"
      "a workspace kept between calls, no allocation after the first)\n",
      runs);
  std::printf("%-9s %6s %6s %7s %7s %8s %8s %7s %7s %7s %8s %7s %7s\n", "case", "points", "roi",
              "median", "worst", "full med", "s1 med", "ws med", "x full", "x s1", "x s1 wst",
              "err mm", "err deg");
  for (const auto& f : css_fixtures()) {
    double ms[4][2];
    BoreResult r;
    std::vector<BoreTimes> stages;
    BoreWorkspace ws;
    for (int mode = 0; mode < 4; ++mode) {
      std::vector<double> t;
      const int n = mode == 2 ? std::max(3, runs / 4) : runs;
      for (int i = 0; i < n; ++i) {
        const double t0 = cpu_ms();
        const BoreResult x =
            css_run(f.scan, f.prior, static_cast<CssMode>(mode), mode == 3 ? &ws : nullptr);
        t.push_back(cpu_ms() - t0);
        if (mode == 0) r = x, stages.push_back(x.time_ms);
      }
      std::sort(t.begin(), t.end());
      ms[mode][0] = t[t.size() / 2];
      ms[mode][1] = t.back();
    }
    std::printf("%-9s %6zu %6zu %7.3f %7.3f %8.3f %8.2f %7.3f %7.1f %7.1f %8.1f %7.4f %7.4f\n",
                f.name.c_str(), r.counts.input, r.counts.roi, ms[0][0], ms[0][1], ms[1][0],
                ms[2][0], ms[3][0], ms[1][0] / ms[0][0], ms[2][0] / ms[0][0], ms[2][1] / ms[0][1],
                (r.entrance - f.scan.truth.entrance).norm(),
                std::acos(std::min(1.0, std::abs(r.axis.dot(f.scan.truth.axis)))) * 180.0 /
                    std::numbers::pi);
    const BoreTimes s = median_stages(stages);
    std::printf(
        "          stages (median wall ms): roi %.3f normals %.3f segmentation %.3f "
        "rsf %.3f refine %.3f; stride %zu, %zu queries, %zu wall, %zu refine points\n",
        s.roi, s.normals, s.segmentation, s.rsf, s.refine, r.counts.stride, r.counts.normal_queries,
        r.counts.wall, r.counts.refine_inliers);
  }
}

// Tables 4.1-4.4 of the thesis on the benchmark scan (test/bench/bore_thesis_tables.hpp).
void thesis_tables(int trials) {
  const Fixture& f = fixture(false);
  bench::thesis_tables_41_42(f.wall, f.wall_normals, f.prior, f.scan.truth, trials);
  bench::thesis_table_43(f.wall, f.wall_normals, f.prior, trials);
  bench::thesis_table_44(std::max(3, trials / 10));
}

// Accuracy per CSS case over `seeds` held-out seeds (1001, 1002, ...: never those of the tests
// or of the timed cases), the three pipelines of CssMode on the same scans: median and worst
// entrance distance, axis angle and |radius error| against the ground truth.
void css_accuracy(int seeds) {
  const char* names[] = {"default", "full region", "session 1"};
  std::printf("\nCSS density, accuracy over %d held-out seeds (median / worst)\n", seeds);
  std::printf("%-9s %-12s %17s %17s %17s %5s\n", "case", "pipeline", "entrance mm", "axis deg",
              "|radius| mm", "found");
  for (const auto& c : bench::css_bore_cases()) {
    std::vector<double> e[3], a[3], r[3];
    int found[3] = {0, 0, 0};
    for (int s = 0; s < seeds; ++s) {
      sim::SyntheticBoreOptions so = c.scan;
      so.seed = 1001 + static_cast<std::uint64_t>(s);
      const sim::SyntheticBoreScan scan = sim::make_synthetic_bore(so);
      const BorePrior prior = bench::css_prior(scan.truth);
      for (int m = 0; m < 3; ++m) {
        const BoreResult x = css_run(scan, prior, static_cast<CssMode>(m));
        if (!x.found) continue;
        ++found[m];
        e[m].push_back((x.entrance - scan.truth.entrance).norm());
        a[m].push_back(std::acos(std::min(1.0, std::abs(x.axis.dot(scan.truth.axis)))) * 180.0 /
                       std::numbers::pi);
        r[m].push_back(std::abs(x.radius - scan.truth.radius));
      }
    }
    const auto mw = [](std::vector<double> v) {
      if (v.empty()) return std::pair<double, double>{NAN, NAN};
      std::sort(v.begin(), v.end());
      return std::pair<double, double>{v[v.size() / 2], v.back()};
    };
    for (int m = 0; m < 3; ++m) {
      const auto [em, ew] = mw(e[m]);
      const auto [am, aw] = mw(a[m]);
      const auto [rm, rw] = mw(r[m]);
      std::printf("%-9s %-12s %8.4f %8.4f %8.4f %8.4f %8.4f %8.4f %2d/%-2d\n", m == 0 ? c.name : "",
                  names[m], em, ew, am, aw, rm, rw, found[m], seeds);
    }
  }
}

// The one-sigma tilt (rad) of a plane fitted to a blind bore's visible bottom (the scan points
// within 0.3 mm of the true bottom and 0.9 r of the axis; the truth only selects them): what a
// flat bottom normal to the axis could add to the axis, were that assumed.
double bottom_tilt_sigma(const sim::SyntheticBoreScan& scan, double depth) {
  const auto& t = scan.truth;
  std::vector<Eigen::Vector3d> pts;
  for (const auto& p : scan.cloud.points) {
    const Eigen::Vector3d d = p - t.entrance;
    const double h = d.dot(t.axis);
    if (std::abs(h + depth) < 0.3 && (d - h * t.axis).norm() < 0.9 * t.radius) pts.push_back(p);
  }
  const pca::Plane plane = pca::fit_plane(pts);
  if (!plane.valid || pts.size() < 10) return 0.0;
  // sigma^2 (sum of in-plane offsets' outer products)^-1 over the tilt's two directions.
  const Eigen::Vector3d e1 = plane.normal.unitOrthogonal(), e2 = plane.normal.cross(e1);
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) {
    const Eigen::Vector2d u((p - plane.point).dot(e1), (p - plane.point).dot(e2));
    m += u * u.transpose();
  }
  const double var =
      plane.rms * plane.rms * static_cast<double>(pts.size()) / static_cast<double>(pts.size() - 3);
  return std::sqrt(var * m.inverse().trace());
}

// Where the entrance error comes from (--css_entrance=N): per CSS case, over tuning seeds 1..N
// and held-out seeds 1001.., the median entrance error split into its height (the true entrance's
// distance from the fitted plane: the plane's error) and its part across the true axis (the
// fitted axis's offset where it meets the plane), beside the fit's own sigma_offset and the
// plane's tilt from the truth.
void css_entrance(int seeds) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  std::printf("\nCSS density, entrance error split, %d seeds per set (medians)\n", seeds);
  std::printf("%-9s %-9s %9s %9s %9s %9s %10s %9s %9s\n", "case", "seeds", "entr mm",
              "worst", "height mm", "across mm", "sig off mm", "tilt deg", "found");
  const auto med = [](std::vector<double> v) {
    if (v.empty()) return std::nan("");
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  for (const auto& c : bench::css_bore_cases()) {
    for (const std::uint64_t first : {std::uint64_t{1}, std::uint64_t{1001}}) {
      std::vector<double> e, h, a, so, tilt;
      for (int i = 0; i < seeds; ++i) {
        sim::SyntheticBoreOptions o = c.scan;
        o.seed = first + static_cast<std::uint64_t>(i);
        const sim::SyntheticBoreScan scan = sim::make_synthetic_bore(o);
        const auto& t = scan.truth;
        const BoreResult x = css_run(scan, bench::css_prior(t), CssMode::kDefault);
        if (!x.found) continue;
        const Eigen::Vector3d d = x.entrance - t.entrance;
        e.push_back(d.norm());
        h.push_back(std::abs(d.dot(x.plane_normal)));
        a.push_back((d - d.dot(t.axis) * t.axis).norm());
        so.push_back(x.sigma_offset);
        tilt.push_back(std::acos(std::min(1.0, std::abs(x.plane_normal.dot(t.plane_normal)))) *
                       kDeg);
      }
      const double worst = e.empty() ? NAN : *std::max_element(e.begin(), e.end());
      std::printf("%-9s %4d..%-4d %9.4f %9.4f %9.4f %9.4f %10.4f %9.4f %5zu/%d\n",
                  first == 1 ? c.name : "", static_cast<int>(first),
                  static_cast<int>(first) + seeds - 1, med(e), worst, med(h), med(a), med(so),
                  med(tilt), e.size(), seeds);
    }
  }
}

// How far the scans determine each CSS case's axis (--axis_bound=N): over tuning seeds 1..N and
// held-out seeds 1001.., the median and worst axis error of the default pipeline beside the
// median one-sigma error its own fit reports (BoreResult::sigma_axis, the Cramer-Rao bound of the
// inlier points under their residual noise; for an unbiased fit the median error is
// sqrt(ln 2) = 0.83 of it), and the median |radius error| beside the median sigma_radius (for a
// Gaussian error the median |error| is 0.67 sigma). A median goal below that bound cannot be met
// from the same points by any unbiased fit, however it is tuned.
void axis_bound(int seeds) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  std::printf("\nCSS density, axis error against the fit's own bound, %d seeds per set\n", seeds);
  std::printf("%-9s %-9s %9s %9s %11s %11s %9s %8s %8s %10s %10s\n", "case", "seeds", "med deg",
              "worst", "sigma deg", "0.83 sigma", "err/bnd", "inliers", "found", "|r| med mm",
              "sigma r");
  for (const auto& c : bench::css_bore_cases()) {
    for (const std::uint64_t first : {std::uint64_t{1}, std::uint64_t{1001}}) {
      std::vector<double> err, sig, n, bottom, both, rerr, rsig;
      for (int i = 0; i < seeds; ++i) {
        sim::SyntheticBoreOptions so = c.scan;
        so.seed = first + static_cast<std::uint64_t>(i);
        const sim::SyntheticBoreScan scan = sim::make_synthetic_bore(so);
        const double sb = so.depth > 0.0 ? bottom_tilt_sigma(scan, so.depth) : 0.0;
        const BoreResult x = css_run(scan, bench::css_prior(scan.truth), CssMode::kDefault);
        if (!x.found || !(x.sigma_axis > 0.0)) continue;
        err.push_back(std::acos(std::min(1.0, std::abs(x.axis.dot(scan.truth.axis)))) * kDeg);
        sig.push_back(x.sigma_axis * kDeg);
        n.push_back(static_cast<double>(x.counts.refine_inliers));
        rerr.push_back(std::abs(x.radius - scan.truth.radius));
        rsig.push_back(x.sigma_radius);
        if (sb > 0.0) {
          bottom.push_back(sb * kDeg);
          both.push_back(1.0 / std::sqrt(1.0 / (x.sigma_axis * x.sigma_axis) + 1.0 / (sb * sb)) *
                         kDeg);
        }
      }
      const auto med = [](std::vector<double> v) {
        if (v.empty()) return std::nan("");
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
      };
      const double worst = err.empty() ? NAN : *std::max_element(err.begin(), err.end());
      const double e = med(err), sg = med(sig);
      std::printf("%-9s %4d..%-4d %9.4f %9.4f %11.4f %11.4f %9.2f %8.0f %5zu/%d %10.4f %10.4f\n",
                  first == 1 ? c.name : "", static_cast<int>(first),
                  static_cast<int>(first) + seeds - 1, e, worst, sg, std::sqrt(std::log(2.0)) * sg,
                  e / (std::sqrt(std::log(2.0)) * sg), med(n), err.size(), seeds, med(rerr),
                  med(rsig));
      if (!bottom.empty()) {
        std::printf(
            "          a flat bottom taken as normal to the axis (not assumed by the "
            "detector) would add: bottom tilt sigma %.4f deg, combined sigma %.4f deg\n",
            med(bottom), med(both));
      }
    }
  }
}

}  // namespace
}  // namespace rangefit

int main(int argc, char** argv) {
  int table_runs = 0, accuracy_seeds = 0, thesis_trials = 0, shape_runs = 0, shape_seeds = 0;
  int bound_seeds = 0, entrance_seeds = 0;
  bool held_out = false;
  for (int i = 1; i < argc; ++i) {
    int* value = nullptr;
    std::size_t len = 0;
    if (std::strcmp(argv[i], "--held_out") == 0) held_out = true;
    if (std::strncmp(argv[i], "--shape_table", 13) == 0) value = &shape_runs, len = 13;
    if (std::strncmp(argv[i], "--shape_accuracy", 16) == 0) value = &shape_seeds, len = 16;
    if (held_out && std::strcmp(argv[i], "--held_out") == 0) {
      for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
      --argc;
      --i;
      continue;
    }
    if (std::strncmp(argv[i], "--css_table", 11) == 0) value = &table_runs, len = 11;
    if (std::strncmp(argv[i], "--css_accuracy", 14) == 0) value = &accuracy_seeds, len = 14;
    if (std::strncmp(argv[i], "--thesis_tables", 15) == 0) value = &thesis_trials, len = 15;
    if (std::strncmp(argv[i], "--axis_bound", 12) == 0) value = &bound_seeds, len = 12;
    if (std::strncmp(argv[i], "--css_entrance", 14) == 0) value = &entrance_seeds, len = 14;
    if (!value) continue;
    *value = argv[i][len] == '=' ? std::atoi(argv[i] + len + 1)
                                 : (len == 11 || len == 13   ? 40
                                    : len == 14 || len == 16 ? 10
                                    : len == 12              ? 30
                                                             : 100);
    for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
    --argc;
    --i;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  if (table_runs > 0) rangefit::css_table(table_runs);
  if (accuracy_seeds > 0) rangefit::css_accuracy(accuracy_seeds);
  if (bound_seeds > 0) rangefit::axis_bound(bound_seeds);
  if (entrance_seeds > 0) rangefit::css_entrance(entrance_seeds);
  if (thesis_trials > 0) rangefit::thesis_tables(thesis_trials);
  if (shape_runs > 0) rangefit::bench::shape_table(shape_runs);
  if (shape_seeds > 0) rangefit::bench::shape_accuracy(shape_seeds, held_out, !held_out);
  benchmark::Shutdown();
  return 0;
}
