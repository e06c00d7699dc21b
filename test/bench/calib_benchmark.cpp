// Calibration time on the densest inputs the calibration tests use, as ratios to baselines
// measured in the same run (the machine is shared, so absolute times are noisy):
// - CSS mount (calib/css_calibration.hpp): eight robot poses of the precision sphere, 84
//   revolutions each at 0.06 mm noise (test/calib/css_fixtures.hpp; ~218,000 samples, as many as
//   the service's four dense poses give), the fit from the configured mount. Baseline: one pass
//   over the same samples that puts each into the robot's base frame under the configured mount,
//   which is what fusing them into a cloud costs.
// - Stripe rig (calib/stripe_calibration.hpp): two cameras of one laser plane, one on each side,
//   each sweeping the cube standing on a corner at 2 mm profiles and 0.06 mm noise
//   (test/calib/calib_fixtures.hpp two_sided_rig). Baseline: camera a calibrated on its own
//   from its sweep, so the ratio is what joining the second camera costs.
//
//   calib_benchmark [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include "calib/css_calibration.hpp"
#include "calib/stripe_calibration.hpp"
#include "test/calib/calib_fixtures.hpp"
#include "test/calib/css_fixtures.hpp"

namespace {

using namespace rangefit;

struct CssInput {
  hal::CssGeometry g;
  std::vector<calib::CssSphereScan> scans;
  std::size_t samples = 0;
};

const CssInput& css_input() {
  static const CssInput in = [] {
    CssInput c;
    c.scans = test::css_sphere_scans(c.g, test::perturbed_mount(c.g, 3), 0.06, 7, 84);
    for (const auto& s : c.scans) c.samples += s.samples.size();
    return c;
  }();
  return in;
}

void BM_CssMountFusePass(benchmark::State& state) {
  const CssInput& in = css_input();
  const Eigen::Isometry3d mount = calib::nominal_mount(in.g);
  for (auto _ : state) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& scan : in.scans) {
      for (const auto& s : scan.samples) {
        const Eigen::Vector3d q = in.g.sensor_point(s.beam_rad, s.range_mm);
        sum += scan.T_base_joint *
               (Eigen::AngleAxisd(s.omega_rad, Eigen::Vector3d::UnitY()) * (mount * q));
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["samples"] = static_cast<double>(in.samples);
}
BENCHMARK(BM_CssMountFusePass)->Unit(benchmark::kMillisecond);

void BM_CssMountCalibration(benchmark::State& state) {
  const CssInput& in = css_input();
  calib::CssCalibrationOptions options;
  options.sphere_radius_mm = test::kRadius;
  int iterations = 0;
  for (auto _ : state) {
    const calib::CssCalibrationResult r = calib::calibrate_css_mount(in.scans, in.g, 0.0, options);
    if (!r.ok) state.SkipWithError(r.reason.c_str());
    iterations = r.iterations;
  }
  state.counters["samples"] = static_cast<double>(in.samples);
  state.counters["lm_iterations"] = iterations;
}
BENCHMARK(BM_CssMountCalibration)->Unit(benchmark::kMillisecond)->MinTime(3.0);

const test::Rig& rig() {
  static const test::Rig r = test::two_sided_rig(1, {.sigma_mm = 0.06, .seed = 11});
  return r;
}

void BM_StripeOneCamera(benchmark::State& state) {
  const test::Rig& r = rig();
  calib::StripeCalibrationInput in;
  in.profiles = r.a.profiles;
  in.axis_mm = r.a.axis;
  in.T_table_cube = test::cube_between_cameras();
  for (auto _ : state) {
    const auto result = calib::calibrate_stripe_cell(in, hal::StripeCellGeometry{});
    if (!result.ok) state.SkipWithError(result.reason.c_str());
  }
  state.counters["profiles"] = static_cast<double>(r.a.profiles.size());
}
BENCHMARK(BM_StripeOneCamera)->Unit(benchmark::kMillisecond);

void BM_StripeRigTwoCameras(benchmark::State& state) {
  const test::Rig& r = rig();
  for (auto _ : state) {
    const auto result = test::calibrate_rig(r.a, r.b);
    if (!result.ok) state.SkipWithError(result.reason.c_str());
  }
  state.counters["profiles"] = static_cast<double>(r.a.profiles.size() + r.b.profiles.size());
}
BENCHMARK(BM_StripeRigTwoCameras)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
