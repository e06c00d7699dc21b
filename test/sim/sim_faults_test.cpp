#include <gtest/gtest.h>

#include <cmath>

#include "sim/css_simulator.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"
#include "sim_test_scenes.hpp"

namespace rangefit::sim {
namespace sim_faults_test {

using std::chrono::milliseconds;

CssScanOptions noisy(std::uint64_t seed) {
  CssScanOptions o;
  o.deflection_rad = 0.5 * 3.14159265358979323846 / 180.0;
  o.seed = seed;
  o.css_faults.range_noise_sigma_mm = 0.06;  // thesis: 60 um depth resolution
  o.css_faults.outlier_probability = 0.01;
  o.css_faults.ghost_probability = 0.01;
  o.css_faults.drop_probability = 0.1;
  o.joint_faults.stamp_jitter_sigma = std::chrono::microseconds(50);
  return o;
}

std::vector<hal::CssRevolution> scan(const Scene& scene, const CssScanOptions& o) {
  const RayCaster caster(scene);
  SimClock clock;
  CssRig rig(scene, caster, o, clock);
  std::vector<hal::CssRevolution> out;
  EXPECT_TRUE(rig.css().start());
  while (clock.now() < rig.scan_end()) rig.css().read(out, milliseconds(300));
  return out;
}

bool same(const std::vector<hal::CssRevolution>& a, const std::vector<hal::CssRevolution>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].sequence != b[i].sequence || a[i].stamp != b[i].stamp) return false;
    for (int k = 0; k < hal::CssRevolution::kSamples; ++k) {
      const float x = a[i].range_mm[k], y = b[i].range_mm[k];
      if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
    }
  }
  return true;
}

TEST(SimFaults, SameSeedGivesTheSameScanAndAnotherSeedDoesNot) {
  const Scene scene = testing::css_analytic_scene();
  const auto a = scan(scene, noisy(7));
  const auto b = scan(scene, noisy(7));
  const auto c = scan(scene, noisy(8));
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(same(a, b));
  EXPECT_FALSE(same(a, c));
}

TEST(SimFaults, DroppedRevolutionsShowAsSequenceGapsAndInHealth) {
  const Scene scene = testing::css_analytic_scene();
  const RayCaster caster(scene);
  SimClock clock;
  CssRig rig(scene, caster, noisy(3), clock);
  std::vector<hal::CssRevolution> revs;
  ASSERT_TRUE(rig.css().start());
  while (clock.now() < rig.scan_end()) rig.css().read(revs, milliseconds(300));
  std::uint64_t missing = 0;
  for (std::size_t i = 1; i < revs.size(); ++i)
    missing += revs[i].sequence - revs[i - 1].sequence - 1;
  const hal::DeviceHealth h = rig.css().health();
  EXPECT_GT(h.counters.gaps, 0u);
  EXPECT_GE(h.counters.gaps, missing);
  EXPECT_EQ(h.counters.samples, revs.size());
  EXPECT_FALSE(h.message.empty());
}

TEST(SimFaults, NoiseMovesRangesByAboutSigma) {
  const Scene scene = testing::css_analytic_scene();
  CssScanOptions o = noisy(5);
  o.css_faults.outlier_probability = 0.0;
  o.css_faults.ghost_probability = 0.0;
  o.css_faults.drop_probability = 0.0;
  const RayCaster caster(scene);
  SimClock clock;
  CssRig rig(scene, caster, o, clock);
  std::vector<hal::CssRevolution> revs;
  ASSERT_TRUE(rig.css().start());
  while (clock.now() < rig.scan_end()) rig.css().read(revs, milliseconds(300));
  double sum2 = 0.0;
  int n = 0;
  for (const auto& rev : revs) {
    const CssRevolutionTruth t = rig.cast_revolution(rev.sequence);
    for (int i = 0; i < hal::CssRevolution::kSamples; ++i) {
      if (std::isnan(t.range_mm[i])) continue;
      const double e = rev.range_mm[i] - t.range_mm[i];
      sum2 += e * e;
      ++n;
    }
  }
  ASSERT_GT(n, 1000);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.06, 0.006);
}

TEST(SimFaults, DisconnectMidScanIsReportedAndRecovered) {
  const Scene scene = testing::css_analytic_scene();
  CssScanOptions o;
  o.deflection_rad = 0.5 * 3.14159265358979323846 / 180.0;
  o.css_faults.disconnect_after = milliseconds(800);
  o.css_faults.disconnect_for = milliseconds(700);
  const RayCaster caster(scene);
  SimClock clock;
  CssRig rig(scene, caster, o, clock);
  ASSERT_TRUE(rig.css().start());
  std::vector<hal::CssRevolution> revs;
  bool saw_disconnect = false;
  while (clock.now() < rig.scan_end()) {
    rig.css().read(revs, milliseconds(50));
    saw_disconnect |= rig.css().health().state == hal::DeviceState::kDisconnected;
  }
  EXPECT_TRUE(saw_disconnect);
  const hal::DeviceHealth h = rig.css().health();
  EXPECT_EQ(h.state, hal::DeviceState::kStreaming);
  EXPECT_EQ(h.counters.reconnects, 1u);
  EXPECT_GE(h.counters.gaps, 4u);  // ~0.7 s at 7 Hz
}

TEST(SimClock, AsFastAsPossibleJumpsToTheNextEventAndNeverGoesBack) {
  SimClock clock;
  const hal::Timestamp t0 = clock.now();
  clock.sleep_until(t0 + std::chrono::seconds(25));
  EXPECT_EQ(clock.now(), t0 + std::chrono::seconds(25));
  clock.sleep_until(t0);
  EXPECT_EQ(clock.now(), t0 + std::chrono::seconds(25));
}

TEST(SimClock, ScaledClockRunsAheadOfRealTime) {
  SimClock clock(1000.0);
  const hal::Timestamp t0 = clock.now();
  clock.sleep_until(t0 + std::chrono::seconds(2));  // ~2 ms of real time
  EXPECT_GE(clock.now(), t0 + std::chrono::seconds(2));
}

TEST(SceneLoader, ReadsPrimitivesPosesAndMounts) {
  const Scene s = parse_scene(R"(
[[object]]
name = "table"
type = "plane"
size = [400, 300]
[[object]]
name = "can"
type = "cylinder"
radius = 30
height = 100
position = [10, 20, 50]
z_axis = [0, 0, 1]
[[object]]
name = "plate"
type = "bore_plate"
[[object.bore]]
name = "b12"
diameter = 12
[sensors.css]
position = [0, 0, -285.8]
)",
                              "inline.toml", ".");
  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_EQ(s.objects[1].T_world_object.translation(), Eigen::Vector3d(10, 20, 50));
  ASSERT_EQ(s.bores.size(), 1u);
  EXPECT_DOUBLE_EQ(s.bores[0].diameter_mm, 12.0);
  EXPECT_DOUBLE_EQ(s.mounts.T_scene_css.translation().z(), -285.8);
}

TEST(SceneLoader, ErrorsNameTheFileLineAndField) {
  try {
    parse_scene("[[object]]\nname = \"x\"\ntype = \"sphere\"\nradius = -1\n", "bad.toml", ".");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:4"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("object[0].radius: must be positive"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse_scene("", "empty.toml", "."), SceneError);
  EXPECT_THROW(parse_scene("[[object]\n", "broken.toml", "."), SceneError);
  EXPECT_THROW(load_scene("/nonexistent/scene.toml"), SceneError);
}

TEST(RayCaster, EmbreeAgreesWithBruteForceOnAMeshAndPrimitives) {
  const Scene scene = testing::css_bore_scene(BoreKind::kNotched, 20.0);
  Scene mixed = testing::css_analytic_scene();
  mixed.objects.push_back(scene.objects[0]);
  const RayCaster caster(mixed);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const double oy = u(rng), ox = u(rng);  // in the order of the recorded data
    const Eigen::Vector3d o(ox, oy, 285.8 + 100.0);
    const double ty = u(rng), tx = u(rng);
    const Eigen::Vector3d target(tx, ty, 285.8 - 10.0);
    const Ray r{o, (target - o).normalized(), 0.0, 1e4};
    const Hit a = caster.cast(r), b = caster.cast_brute_force(r);
    ASSERT_EQ(a.valid, b.valid);
    if (!a.valid) continue;
    ++hits;
    EXPECT_NEAR(a.t, b.t, 1e-6);
  }
  EXPECT_GT(hits, 1000);
}

}  // namespace sim_faults_test
}  // namespace rangefit::sim
