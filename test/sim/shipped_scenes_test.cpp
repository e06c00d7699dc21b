#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "detect/object/superquadric.hpp"
#include "sim/css_simulator.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::sim {
namespace shipped_scenes_test {

std::string scene_path(const char* name) {
  return std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/" + name;
}

TEST(ShippedScenes, BorePlateHasEveryBoreKindFrom4To38Millimetres) {
  const Scene s = load_scene(scene_path("bore_plate.toml"));
  ASSERT_EQ(s.bores.size(), 6u);
  double lo = 1e9, hi = 0.0;
  for (const auto& b : s.bores) {
    lo = std::min(lo, b.diameter_mm);
    hi = std::max(hi, b.diameter_mm);
  }
  EXPECT_DOUBLE_EQ(lo, 4.0);
  EXPECT_DOUBLE_EQ(hi, 38.0);
}

TEST(ShippedScenes, CssScanOfTheBorePlateSeesTheBoreUnderTheSensor) {
  const Scene s = load_scene(scene_path("bore_plate.toml"));
  const RayCaster caster(s);
  SimClock clock;
  CssScanOptions o;
  const CssRig rig(s, caster, o, clock);
  int valid = 0, in_bore = 0;
  for (std::uint64_t k = 0; k < rig.revolutions_in_scan(); k += 5) {
    const CssRevolutionTruth t = rig.cast_revolution(k);
    for (int i = 0; i < hal::CssRevolution::kSamples; ++i) {
      if (std::isnan(t.range_mm[i])) continue;
      ++valid;
      in_bore += t.point_scene[i].z() < 285.8 - 1.0 ? 1 : 0;
    }
  }
  EXPECT_GT(valid, 10000);
  EXPECT_GT(in_bore, 100);
}

TEST(ShippedScenes, StripeScanOfTheFigure518SceneLandsOnTheSuperquadrics) {
  for (const char* name : {"table_top_fig5_18.toml", "cluttered_mallet.toml"}) {
    const Scene s = load_scene(scene_path(name));
    const RayCaster caster(s);
    SimClock clock;
    StripeCellOptions o;
    StripeCell cell(s, caster, o, clock);
    int on_parts = 0;
    for (double axis = 0.0; axis <= 400.0; axis += 10.0) {
      const ProfileTruth t = cast_profile(
          caster, o.geometry.ranger, s.mounts.T_scene_stripe * o.geometry.T_world_ranger(axis));
      for (std::size_t i = 0; i < t.object.size(); ++i) {
        if (t.object[i] < 0) continue;
        const SceneObject& obj = s.objects[static_cast<std::size_t>(t.object[i])];
        const auto* sq = std::get_if<SuperquadricShape>(&obj.shape);
        if (!sq) continue;
        ++on_parts;
        ASSERT_NEAR(metric_world(sq->model, obj.T_world_object, t.point_scene[i]), 1.0, 1e-4)
            << name << " " << obj.name;
      }
    }
    EXPECT_GT(on_parts, 500) << name;
  }
}

}  // namespace shipped_scenes_test
}  // namespace rangefit::sim
