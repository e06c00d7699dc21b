#pragma once
// Cone and elliptic bores (test/detect/bore_test_cases.hpp: a 90 deg countersink Ø12 into Ø6, a
// pure 90 deg cone, a 3 deg taper, a 10 x 9 mm ellipse, at the CSS's density) for
// bore_benchmark: BM_Shape times each beside a plain cylinder of the same size on the same kind
// of scan (Ø12 beside the countersink and the cone, Ø10 beside the taper and the ellipse);
// --shape_table=N prints the median thread-CPU time per detection of each and its ratio to its
// cylinder, measured interleaved in the same run; --shape_accuracy=N the median and worst
// errors over the tuning seeds 1..N, or, with --held_out, over the held-out seeds 1001...

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <vector>

#include "detect/bore/bore_detector.hpp"
#include "test/detect/bore_test_cases.hpp"

namespace rangefit::bench {

inline constexpr test::ShapeKind kShapeKinds[] = {test::ShapeKind::kCountersink,
                                                  test::ShapeKind::kCone, test::ShapeKind::kTaper,
                                                  test::ShapeKind::kEllipse};

// The plain cylinder a shape is timed against: the same scan settings and pose, the shape's
// largest radius, no cone or ellipse.
inline sim::SyntheticBoreOptions cylinder_twin(test::ShapeKind kind, std::uint64_t seed) {
  sim::SyntheticBoreOptions o = test::shape_scan_options(kind, seed);
  o.radius = std::max(o.radius, o.cone_radius);
  o.cone_radius = 0.0;
  o.radius2 = 0.0;
  o.depth = 12.0;
  return o;
}

struct ShapeFixture {
  sim::SyntheticBoreScan scan, cylinder;
  BorePrior prior, cylinder_prior;
};

inline const ShapeFixture& shape_fixture(test::ShapeKind kind) {
  static ShapeFixture f[4];
  ShapeFixture& x = f[static_cast<int>(kind)];
  if (!x.scan.cloud.empty()) return x;
  constexpr std::uint64_t kSeed = 1;  // a tuning seed: timing only
  x.scan = sim::make_synthetic_bore(test::shape_scan_options(kind, kSeed));
  x.prior = test::shape_prior(x.scan.truth, kSeed);
  x.cylinder = sim::make_synthetic_bore(cylinder_twin(kind, kSeed));
  x.cylinder_prior = test::perturbed_prior(x.cylinder.truth, kSeed);
  return x;
}

inline BoreResult shape_run(const sim::SyntheticBoreScan& scan, const BorePrior& prior) {
  BoreOptions o;
  o.view_dir = scan.truth.view_dir;
  return detect_bore(scan.cloud, prior, o);
}

inline double shape_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

// range(0): the kind; range(1): 0 the shape, 1 its cylinder twin.
inline void BM_Shape(benchmark::State& state) {
  const auto kind = static_cast<test::ShapeKind>(state.range(0));
  const ShapeFixture& f = shape_fixture(kind);
  const bool twin = state.range(1) == 1;
  state.SetLabel(std::string(test::shape_name(kind)) + (twin ? " cylinder twin" : ""));
  BoreResult r;
  for (auto _ : state) {
    r = twin ? shape_run(f.cylinder, f.cylinder_prior) : shape_run(f.scan, f.prior);
    benchmark::DoNotOptimize(r);
  }
  state.counters["found"] = r.found;
  state.counters["points"] = static_cast<double>(r.counts.input);
  state.counters["fit_points"] = static_cast<double>(r.counts.refine_inliers);
}

inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

inline void shape_table(int runs) {
  std::printf(
      "\nCone and elliptic bores at the CSS density, %d runs each, interleaved with the cylinder\n"
      "twin (thread CPU ms per detection, median; ratio = shape / cylinder, same run)\n",
      runs);
  std::printf("%-26s %7s %9s %9s %6s %9s\n", "case", "points", "shape ms", "cyl ms", "ratio",
              "fit pts");
  for (const test::ShapeKind kind : kShapeKinds) {
    const ShapeFixture& f = shape_fixture(kind);
    std::vector<double> a, b;
    BoreResult r;
    for (int i = 0; i < runs; ++i) {
      double t0 = shape_cpu_ms();
      r = shape_run(f.scan, f.prior);
      a.push_back(shape_cpu_ms() - t0);
      t0 = shape_cpu_ms();
      benchmark::DoNotOptimize(shape_run(f.cylinder, f.cylinder_prior));
      b.push_back(shape_cpu_ms() - t0);
    }
    std::printf("%-26s %7zu %9.3f %9.3f %6.2f %9zu\n", test::shape_name(kind), r.counts.input,
                median(a), median(b), median(a) / median(b), r.counts.refine_inliers);
  }
}

// Errors of one detection against the truth: entrance mm, axis deg, half-angle deg (cone),
// radius and radius2 mm (radius: at the entrance / along the major axis).
struct ShapeErrors {
  double entrance = NAN, axis = NAN, angle = NAN, radius = NAN, radius2 = NAN;
};

inline ShapeErrors shape_errors(const BoreResult& r, const sim::SyntheticBoreTruth& t) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  ShapeErrors e;
  e.entrance = (r.entrance - t.entrance).norm();
  e.axis = std::acos(std::min(1.0, std::abs(r.axis.dot(t.axis)))) * kDeg;
  if (r.shape && r.shape->cone) {
    e.angle = std::abs(r.shape->half_angle - t.half_angle) * kDeg;
    e.radius = std::abs(r.radius - t.cone_radius);
  } else if (r.shape) {
    e.radius = std::abs(r.radius - t.radius);
    e.radius2 = std::abs(r.shape->radius2 - t.radius2);
  }
  return e;
}

// Median / worst per error, and how many seeds meet the tests' limits (found; entrance 0.1 mm,
// axis 0.2 deg; half-angle 0.2 deg; ellipse radii 0.02 mm).
inline void shape_accuracy(int seeds, bool held_out, bool verbose = false) {
  const std::uint64_t first = held_out ? test::kShapeHeldOutSeed : 1;
  std::printf("\nCone and elliptic bores, accuracy over %s seeds %d..%d (median / worst)\n",
              held_out ? "held-out" : "tuning", static_cast<int>(first),
              static_cast<int>(first) + seeds - 1);
  std::printf("%-26s %17s %17s %17s %17s %17s %8s\n", "case", "entrance mm", "axis deg",
              "half-angle deg", "radius mm", "radius2 mm", "in spec");
  for (const test::ShapeKind kind : kShapeKinds) {
    std::vector<double> v[5];
    int ok = 0;
    for (int s = 0; s < seeds; ++s) {
      const std::uint64_t seed = first + static_cast<std::uint64_t>(s);
      const auto scan = sim::make_synthetic_bore(test::shape_scan_options(kind, seed));
      const BoreResult r = shape_run(scan, test::shape_prior(scan.truth, seed));
      if (!r.found) continue;
      const ShapeErrors e = shape_errors(r, scan.truth);
      const double x[5] = {e.entrance, e.axis, e.angle, e.radius, e.radius2};
      for (int k = 0; k < 5; ++k) {
        if (!std::isnan(x[k])) v[k].push_back(x[k]);
      }
      const bool in_spec = e.entrance < 0.1 && e.axis < 0.2 && !(e.angle >= 0.2) &&
                           !(e.radius2 >= 0.02) && (r.shape->cone || e.radius < 0.02);
      ok += in_spec;
      if (!in_spec && verbose) {
        std::printf("  out of spec: %s seed %d: entrance %.4f axis %.4f angle %.4f radius %.4f "
                    "radius2 %.4f major %.2f deg; %zu points, rms %.4f, rsf seed %d, %d iterations, sigma r %.4f\n",
                    test::shape_name(kind), static_cast<int>(seed), e.entrance, e.axis, e.angle,
                    e.radius, e.radius2,
                    std::acos(std::min(1.0, std::abs(r.shape->major_axis.dot(
                                                scan.truth.major_axis)))) * 180.0 / std::numbers::pi,
                    r.counts.refine_inliers, r.shape->rms,
                    r.shape->seeded_by_rsf ? 1 : 0, r.shape->iterations, r.shape->sigma_radius);
      }
    }
    std::printf("%-26s", test::shape_name(kind));
    for (auto& x : v) {
      const double worst = x.empty() ? NAN : *std::max_element(x.begin(), x.end());
      std::printf(" %8.4f %8.4f", median(x), worst);
    }
    std::printf(" %3d/%-3d\n", ok, seeds);
  }
}

}  // namespace rangefit::bench
