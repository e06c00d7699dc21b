#include "calib/css_scan_text.hpp"

#include <gtest/gtest.h>

namespace rangefit::calib {
namespace css_scan_text_test {

TEST(CssScanText, RoundTripsPosesAndSamples) {
  std::vector<CssSphereScan> scans(2);
  const double v[6] = {412.5, -150.0, 396.25, 0.1, -0.2, 1.57};
  scans[0].T_base_joint = pose_from_xyz_rpy(v);
  scans[0].samples = {{-0.0873, 1.5708, 97.125}, {0.01, 2.0, 88.0}};
  scans[1].samples = {{0.0, 0.0, 100.0}};
  const CssScansParse p = parse_css_scans(format_css_scans(scans));
  ASSERT_TRUE(p.scans) << p.error;
  ASSERT_EQ(p.scans->size(), 2u);
  EXPECT_TRUE(p.scans->at(0).T_base_joint.isApprox(scans[0].T_base_joint, 1e-12));
  ASSERT_EQ(p.scans->at(0).samples.size(), 2u);
  EXPECT_DOUBLE_EQ(p.scans->at(0).samples[0].range_mm, 97.125);
  EXPECT_DOUBLE_EQ(p.scans->at(0).samples[1].beam_rad, 2.0);
}

TEST(CssScanText, EmptyAndMalformedInputGiveTheLine) {
  EXPECT_NE(parse_css_scans("", "f").error.find("f:0: empty"), std::string::npos);
  EXPECT_NE(parse_css_scans("rangefit-css-sphere-scans 2\n", "f").error.find("f:1:"),
            std::string::npos);
  EXPECT_NE(
      parse_css_scans("rangefit-css-sphere-scans 1\n1 2 3\n", "f").error.find("f:2: a sample"),
      std::string::npos);
  EXPECT_NE(
      parse_css_scans("rangefit-css-sphere-scans 1\npose 1 2 3 4 5\n", "f").error.find("f:2:"),
      std::string::npos);
  EXPECT_NE(parse_css_scans("rangefit-css-sphere-scans 1\npose 0 0 0 0 0 0\n1 nan 3\n", "f")
                .error.find("f:3:"),
            std::string::npos);
  EXPECT_NE(parse_css_scans("rangefit-css-sphere-scans 1\npose 0 0 0 0 0 0\n1 2 -3\n", "f")
                .error.find("positive"),
            std::string::npos);
}

}  // namespace css_scan_text_test
}  // namespace rangefit::calib
