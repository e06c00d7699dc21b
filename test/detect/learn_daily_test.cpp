// Model learning (detect/learn/model_learning.hpp) of the thesis's daily-life objects (table 5.6:
// cuboid, sphere, cylinder, pyramid, bowl, mouse, mug, cup, sponge) from laser-stripe teach-in
// scans (test/detect/learn_daily.hpp: the pan-tilt head's oblique sweep with a drawn geometry,
// pose and noise; the second view after a turn of the object by 180 deg): the learnt sizes within
// 2 % and shapes within 0.1 of the truth from one view, 1 % and 0.05 from two. One tuning seed
// each here; test/bench/learn_benchmark --daily reports many, tuning and held-out apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <span>
#include <string>

#include "test/detect/learn_daily.hpp"

namespace rangefit {
namespace learn_daily_test {

std::vector<sim::DailyObject> one_part_objects() {
  std::vector<sim::DailyObject> out;
  for (const sim::DailyObject& o : sim::daily_life_objects()) {
    if (o.model.parts.size() == 1) out.push_back(o);
  }
#if defined(__SANITIZE_ADDRESS__)
  out.resize(3);  // ASan+UBSan runs ~10x slower: cuboid, sphere, cylinder
#endif
  return out;
}

void print(const sim::DailyObject& o, int views, const test::DailyLearnt& l) {
  const Superquadric& s = l.result.parts.empty() ? Superquadric{} : l.result.parts[0].shape;
  std::printf(
      "  %s, %d view(s): learnt %.2f %.2f %.2f e %.3f %.3f k %.3f %.3f: size %.4f "
      "shape %.4f, %.0f ms\n",
      o.name.c_str(), views, s.a1, s.a2, s.a3, s.eps1, s.eps2, s.kx, s.ky, l.size, l.shape,
      l.result.total_ms);
}

TEST(LearnDaily, TableFiveSixObjectsFromOneStripeView) {
  for (const sim::DailyObject& o : one_part_objects()) {
    const test::DailyLearnt l = test::learn_daily(o, 1, 1);
    print(o, 1, l);
    ASSERT_TRUE(l.result.learnt()) << o.name << ": " << to_string(l.result.reason);
    EXPECT_LE(l.size, 0.02) << o.name;
    EXPECT_LE(l.shape, 0.1) << o.name;
  }
}

TEST(LearnDaily, TableFiveSixObjectsFromTwoStripeViews) {
  for (const sim::DailyObject& o : one_part_objects()) {
    const test::DailyLearnt l = test::learn_daily(o, 1, 2);
    print(o, 2, l);
    ASSERT_TRUE(l.result.learnt()) << o.name << ": " << to_string(l.result.reason);
    EXPECT_LE(l.size, 0.01) << o.name;
    EXPECT_LE(l.shape, 0.05) << o.name;
  }
}

// The daily-life object `name` learnt from one view on each of `seeds`, within the one-view
// goals (2 %, 0.1).
void expect_learnt_from_one_view(const std::string& name,
                                 std::initializer_list<std::uint64_t> seeds) {
  for (const sim::DailyObject& o : sim::daily_life_objects()) {
    if (o.name != name) continue;
    for (std::uint64_t seed : seeds) {
      const test::DailyLearnt l = test::learn_daily(o, seed, 1);
      print(o, 1, l);
      ASSERT_TRUE(l.result.learnt()) << seed << ": " << to_string(l.result.reason);
      EXPECT_LE(l.size, 0.02) << seed;
      EXPECT_LE(l.shape, 0.1) << seed;
    }
    return;
  }
  FAIL() << "no daily-life object " << name;
}

// A sphere from one oblique view (tuning seeds 8 and 10): with its tapers free the fit turned it
// into an egg 4.5 % long into the unseen side; a taper the seen surface barely shows is given up.
TEST(LearnDaily, TheSphereFromOneViewIsNotAnEgg) { expect_learnt_from_one_view("sphere", {8, 10}); }

// The mouse from one view (tuning seed 42; section eps2 0.5, 45 x 35 mm): its fit ended turned
// by 45 deg, its section a diamond of eps2 1.44 whose points lay 0.77 mm off it.
TEST(LearnDaily, TheMouseFromOneViewIsNotTurnedIntoADiamond) {
  expect_learnt_from_one_view("mouse", {42});
}

// A pyramid from one oblique view (tuning seeds 12 and 17): its tip is 1.6 mm wide on a 30 mm
// base. Fitted on the radial distance, which reads the noise near the tip many times over, the
// fits blunted the tip to 7 mm across and widened the middle by 32 % (seed 12), or turned the
// square section into a diamond (seed 17, eps2 1.94); on the distance from the surface the
// learnt pyramid is the true one.
TEST(LearnDaily, APyramidsTipIsNotBluntedByTheNoiseAroundIt) {
  expect_learnt_from_one_view("pyramid", {12, 17});
}

// The same pyramid from two views (tuning seed 14): its free fit was right (0.9 % long), and its
// taper, 0.91 from the bound, was then held on the bound as a cone's is, which made it 5.5 % long
// with its base 5 % narrow: on the spread points the fit runs on that cost 0.7 % more, but the
// points on the blunt tip lie twice as far off it.
TEST(LearnDaily, APyramidsBluntTipIsNotSharpenedFromTwoViews) {
  for (const sim::DailyObject& o : sim::daily_life_objects()) {
    if (o.name != "pyramid") continue;
    const test::DailyLearnt l = test::learn_daily(o, 14, 2);
    print(o, 2, l);
    ASSERT_TRUE(l.result.learnt()) << to_string(l.result.reason);
    EXPECT_LE(l.size, 0.01);
    EXPECT_LE(l.shape, 0.05);
    const Superquadric& q = l.result.parts.at(0).shape;
    EXPECT_LT(std::max(std::abs(q.kx), std::abs(q.ky)), 0.99) << "the taper is held on its bound";
  }
}

}  // namespace learn_daily_test
}  // namespace rangefit

namespace rangefit {
namespace learn_daily_test {

// The two-part mug of table 5.7 (body 38 38 48, handle 30 23 8 on its side, 90 deg, 50 mm)
// from two views (tuning seeds 1, 2, 3, 4). Its handle joins the body, so the two are one
// cluster (or the views leave the body in two pieces): the cut across the main moment axis found
// no handle, and a cut through the half-seen body gave two halves of it. Seed 3's handle was fitted
// in a wrong shape (its points 0.19 mm off it, the body's 0.023) until it was learnt again.
TEST(LearnDaily, TheMugFromTwoViewsAsBodyAndHandle) {
  const sim::DailyObject mug = sim::daily_life_objects().back();
  ASSERT_EQ(mug.name, "mug-2");
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    const test::DailyLearnt l = test::learn_daily(mug, seed, 2);
    ASSERT_TRUE(l.result.learnt()) << seed << ": " << to_string(l.result.reason);
    ASSERT_EQ(l.result.parts.size(), 2u);
    for (const LearntPart& p : l.result.parts) {
      const Superquadric& s = p.shape;
      std::printf("  seed %llu: %.2f %.2f %.2f e %.3f %.3f, %zu points\n",
                  static_cast<unsigned long long>(seed), s.a1, s.a2, s.a3, s.eps1, s.eps2,
                  p.points);
    }
    EXPECT_LE(l.size, 0.01) << seed;
    EXPECT_LE(l.shape, 0.05) << seed;
    EXPECT_NEAR(l.link_angle_rad, 0.0, 0.02) << seed;
    EXPECT_NEAR(l.link_distance_mm, 0.0, 1.0) << seed;
  }
}

// The two-part mug from one oblique view (tuning seeds 4, 29 and 40), within the one-view goals.
// Seed 4: the handle's first fit came from a cut that held some of the body's points; after one
// reassignment it stayed 7.5 % too large (its points 0.061 mm off it, the true handle's 0.022).
// Seed 29: the handle's fit ended with its thin axis across the handle (8.5 x 45 x 33 mm, its
// points 0.066 mm off it, the body's 0.024), and is learnt again from all its starts.
// Seed 40: the view shows the body's rim and top but not its foot; its fit ended 7 mm above the
// table, 7.4 % short, with its points explained as well as by the true body. The body stands on
// the table, so it is grown down to it.
TEST(LearnDaily, TheMugFromOneViewHasItsHandlesShapeAndStandsOnTheTable) {
  expect_learnt_from_one_view("mug-2", {4, 29, 40});
}

// One view of the mug with its handle behind the body (tuning seed 3: no scan point within
// 1 mm of the handle) is not a two-part object: the learner says so instead of returning two
// pieces of the body.
TEST(LearnDaily, AMugHandleHiddenBehindItsBodyIsSaidNotSeen) {
  const sim::DailyObject mug = sim::daily_life_objects().back();
  const test::DailyLearnt l = test::learn_daily(mug, 3, 1);
  EXPECT_EQ(l.result.reason, LearnReason::kSecondPartNotSeen) << to_string(l.result.reason);
}

}  // namespace learn_daily_test
}  // namespace rangefit
