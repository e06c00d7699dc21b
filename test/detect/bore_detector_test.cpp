#include "detect/bore/bore_detector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "test/detect/bore_test_cases.hpp"

namespace rangefit {
namespace bore_detector_test {

using test::axis_deg;
using test::kRadToDeg;

struct Errors {
  double entrance_mm, axis_deg, radius_mm;
};

Errors errors(const BoreResult& r, const sim::SyntheticBoreTruth& t) {
  return {(r.entrance - t.entrance).norm(),
          std::acos(std::clamp(r.axis.dot(t.axis), -1.0, 1.0)) * kRadToDeg,
          std::abs(r.radius - t.radius)};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TEST(BoreDetector, EveryCaseWithinThesisToleranceAndMedianWithinTarget) {
  std::vector<double> entrance, axis;
  for (const auto& c : test::bore_cases()) {
    const auto scan = sim::make_synthetic_bore(c.scan);
    BoreOptions opt;
    opt.view_dir = scan.truth.view_dir;
    const BoreResult r =
        detect_bore(scan.cloud, test::perturbed_prior(scan.truth, c.scan.seed), opt);
    EXPECT_TRUE(r.found) << c.name << ": " << to_string(r.reason) << " roi " << r.counts.roi
                         << " normals " << r.counts.normals << " plane " << r.counts.plane
                         << " wall " << r.counts.wall << " pairs " << r.counts.axis_pairs
                         << " triangles " << r.counts.triangles;
    if (!r.found) continue;
    const Errors e = errors(r, scan.truth);
    std::printf(
        "%-24s pts %6zu roi %5zu wall %5zu  entrance %.4f mm  axis %.4f deg  radius %+.4f mm"
        "  rsf r %+.4f  2nd %d  %.2f ms\n",
        c.name.c_str(), r.counts.input, r.counts.roi, r.counts.wall, e.entrance_mm, e.axis_deg,
        r.radius - scan.truth.radius, r.rsf_radius - scan.truth.radius, r.second_fit,
        r.time_ms.total);
    EXPECT_LT(e.entrance_mm, 0.3) << c.name;
    EXPECT_LT(e.axis_deg, 0.5) << c.name;
    EXPECT_LT(e.radius_mm, 0.3) << c.name;
    EXPECT_GT(r.axis.dot(scan.truth.view_dir), 0.0) << c.name << ": axis must point to the sensor";
    entrance.push_back(e.entrance_mm);
    axis.push_back(e.axis_deg);
  }
  std::printf("median entrance %.4f mm, median axis %.4f deg\n", median(entrance), median(axis));
  EXPECT_LT(median(entrance), 0.1);
  EXPECT_LT(median(axis), 0.25);
}

}  // namespace bore_detector_test
}  // namespace rangefit
