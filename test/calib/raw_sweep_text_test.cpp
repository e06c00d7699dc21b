#include "calib/raw_sweep_text.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rangefit::calib {
namespace raw_sweep_text_test {

TEST(RawSweepText, RoundTripsStripeAndPanTiltSweeps) {
  for (const SweepKind kind : {SweepKind::kStripe, SweepKind::kPanTilt}) {
    RawSweep s;
    s.kind = kind;
    s.points_per_profile = 4;
    for (int r = 0; r < 3; ++r) {
      hal::RangerProfile p;
      p.x_mm = {1.5f, hal::kNoReturn, -2.25f, 3.0f};
      p.z_mm = {400.125f, hal::kNoReturn, 401.0f + static_cast<float>(r), 402.5f};
      s.profiles.push_back(p);
      s.axis_mm.push_back(10.0 * r);
      s.angles.push_back({.pan_rad = 0.1 * r, .tilt_rad = -0.05});
    }
    if (kind == SweepKind::kPanTilt) s.axis_mm.clear();
    const RawSweepParse p = parse_raw_sweep(format_raw_sweep(s));
    ASSERT_TRUE(p.sweep) << p.error;
    ASSERT_EQ(p.sweep->profiles.size(), 3u);
    EXPECT_EQ(p.sweep->kind, kind);
    EXPECT_FLOAT_EQ(p.sweep->profiles[2].z_mm[2], 403.0f);
    EXPECT_TRUE(std::isnan(p.sweep->profiles[1].z_mm[1]));
    if (kind == SweepKind::kStripe) {
      EXPECT_DOUBLE_EQ(p.sweep->axis_mm[2], 20.0);
    } else {
      EXPECT_DOUBLE_EQ(p.sweep->angles[2].pan_rad, 0.2);
    }
  }
}

TEST(RawSweepText, EmptyAndMalformedInputGiveTheLine) {
  EXPECT_NE(parse_raw_sweep("", "f").error.find("f:0: empty"), std::string::npos);
  EXPECT_NE(parse_raw_sweep("rangefit-raw-sweep 2 stripe 4\n", "f").error.find("f:1:"),
            std::string::npos);
  EXPECT_NE(parse_raw_sweep("rangefit-raw-sweep 1 stripe 4\n5 1 2\n", "f").error.find("f:2:"),
            std::string::npos);
  EXPECT_NE(
      parse_raw_sweep("rangefit-raw-sweep 1 stripe 4\np 1\n4 1 2\n", "f").error.find("outside"),
      std::string::npos);
  EXPECT_NE(parse_raw_sweep("rangefit-raw-sweep 1 stripe 4\np nan\n", "f").error.find("f:2:"),
            std::string::npos);
}

}  // namespace raw_sweep_text_test
}  // namespace rangefit::calib
