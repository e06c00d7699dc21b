// Simulator speed: a full 25 s CSS scan (~90,000 beam samples over a bore plate) and a
// ~140,000-point stripe-cell scan, each through the HAL devices with an as-fast-as-possible clock.
// Counters: rays_per_s (Embree path), brute_rays_per_s (every triangle and primitive tested per
// ray, measured in the same run on a sample of the same rays) and speedup = their ratio.
// Run on one core: taskset -c 0 build/test/bench/sim_benchmark
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <string>

#include "hal/css_geometry.hpp"
#include "sim/bore_plate_mesh.hpp"
#include "sim/css_simulator.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::sim {
namespace {

Scene bore_plate_scene() {
  BorePlateSpec spec;
  for (BoreKind k : {BoreKind::kStraight, BoreKind::kChamfered, BoreKind::kNotched}) {
    BoreSpec b;
    b.name = to_string(k);
    b.kind = k;
    b.diameter_mm = 12.0;
    spec.bores.push_back(b);
  }
  BorePlate plate = make_bore_plate(spec);
  Scene s;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(60.0, 0.0, hal::CssGeometry{}.pivot_radius_mm);  // middle bore
  s.objects.push_back({"plate", MeshShape{plate.mesh, "bore_plate"}, T});
  return s;
}

Scene table_scene() {
  Scene s;
  s.objects.push_back({"table", PlaneShape{500.0, 500.0}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(-60.0, 100.0, 50.0);
  s.objects.push_back({"box", BoxShape{Eigen::Vector3d(50.0, 50.0, 100.0)}, T});
  T.translation() = Eigen::Vector3d(40.0, 80.0, 50.0);
  s.objects.push_back({"sphere", SphereShape{50.0}, T});
  T.translation() = Eigen::Vector3d(100.0, 40.0, 50.0);
  s.objects.push_back({"cylinder", CylinderShape{30.0, 100.0}, T});
  return s;
}

// Brute-force rays per second on n of the given rays.
double brute_force_rate(const RayCaster& caster, const std::vector<Ray>& rays, std::size_t n) {
  const auto t0 = std::chrono::steady_clock::now();
  int hits = 0;
  for (std::size_t i = 0; i < n && i < rays.size(); ++i)
    hits += caster.cast_brute_force(rays[i]).valid;
  benchmark::DoNotOptimize(hits);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return static_cast<double>(std::min(n, rays.size())) / s;
}

void BM_CssFullScan(benchmark::State& state) {
  const Scene scene = bore_plate_scene();
  const RayCaster caster(scene);
  std::size_t points = 0, revolutions = 0;
  double elapsed = 0.0;  // s, over all iterations
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    SimClock clock;
    CssRig rig(scene, caster, CssScanOptions{}, clock);
    std::vector<hal::CssRevolution> revs;
    if (!rig.css().start()) return state.SkipWithError("css start failed");
    while (clock.now() < rig.scan_end()) rig.css().read(revs, std::chrono::milliseconds(500));
    points = 0;
    for (const auto& r : revs) {
      for (float x : r.range_mm) points += std::isnan(x) ? 0 : 1;
    }
    revolutions = revs.size();
    elapsed += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  // The primary beams of a revolution, to time the brute-force baseline on the same rays.
  SimClock clock;
  const CssRig rig(scene, caster, CssScanOptions{}, clock);
  const auto& g = rig.options().geometry;
  std::vector<Ray> beams;
  for (int i = 0; i < hal::CssRevolution::kSamples; ++i) {
    const Eigen::Isometry3d T = g.T_world_css(0.0);
    beams.push_back(
        Ray{T * g.laser_point(),
            T.linear() * g.beam_direction(g.beam_angle(i, hal::CssRevolution::kSamples)), 0.0,
            g.max_range_mm});
  }
  const double rays = static_cast<double>(revolutions) * hal::CssRevolution::kSamples;
  const double brute = brute_force_rate(caster, beams, 64);
  state.counters["revolutions"] = static_cast<double>(revolutions);
  state.counters["points"] = static_cast<double>(points);
  state.counters["triangles"] = static_cast<double>(caster.triangle_count());
  state.counters["rays_per_s"] =
      benchmark::Counter(rays, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["brute_rays_per_s"] = brute;
  state.counters["speedup"] = rays * static_cast<double>(state.iterations()) / elapsed / brute;
  state.SetLabel("primary beams only in rays_per_s; return rays add up to one more each");
}
BENCHMARK(BM_CssFullScan)->Unit(benchmark::kMillisecond)->UseRealTime();

// The stripe scan of a scene: table_scene() (exact primitives) or, with the argument 1, the
// fig. 5.18 table top built from STL meshes (data/scenes/table_top_fig5_18_stl.toml, ~9,000
// triangles), where the brute-force baseline has every triangle to test.
void BM_StripeScan140k(benchmark::State& state) {
  const Scene scene = state.range(0) == 0 ? table_scene()
                                          : load_scene(std::string(RANGEFIT_SOURCE_DIR) +
                                                       "/data/scenes/table_top_fig5_18_stl.toml");
  const RayCaster caster(scene);
  std::size_t points = 0, profiles = 0;
  double elapsed = 0.0;  // s, over all iterations
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    SimClock clock;
    StripeCell cell(scene, caster, StripeCellOptions{}, clock);
    if (!cell.axis().enable() || !cell.ranger().start())
      return state.SkipWithError("stripe cell start failed");
    const double travel = state.range(0) == 0 ? 175.0 : 156.0;  // ~140,000 points either way
    if (!cell.axis().move_to(travel, 6.3)) return state.SkipWithError("axis move failed");
    std::vector<hal::RangerProfile> out;
    while (!cell.axis().motion_complete()) cell.ranger().read(out, std::chrono::milliseconds(500));
    points = 0;
    for (const auto& p : out) {
      for (float z : p.z_mm) points += std::isnan(z) ? 0 : 1;
    }
    profiles = out.size();
    elapsed += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  SimClock clock;
  StripeCell cell(scene, caster, StripeCellOptions{}, clock);
  const auto& r = cell.options().geometry.ranger;
  std::vector<Ray> fan;
  const Eigen::Isometry3d T =
      scene.mounts.T_scene_stripe * cell.options().geometry.T_world_ranger(140.0);
  for (int k = 0; k < r.points_per_profile; ++k) {
    fan.push_back(
        Ray{T.translation(), T.linear() * r.ray_direction(k, r.points_per_profile), 0.0, 1e4});
  }
  const double rays = static_cast<double>(profiles) * r.points_per_profile;
  const double brute = brute_force_rate(caster, fan, state.range(0) == 0 ? fan.size() : 64);
  state.counters["triangles"] = static_cast<double>(caster.triangle_count());
  state.counters["profiles"] = static_cast<double>(profiles);
  state.counters["points"] = static_cast<double>(points);
  state.counters["rays_per_s"] =
      benchmark::Counter(rays, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["brute_rays_per_s"] = brute;
  state.counters["speedup"] = rays * static_cast<double>(state.iterations()) / elapsed / brute;
}
BENCHMARK(BM_StripeScan140k)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rangefit::sim

BENCHMARK_MAIN();
