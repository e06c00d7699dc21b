#pragma once
// The scan both bore benchmarks measure on (bore_benchmark and the optional PCL comparison), so
// that their figures stay comparable: a ~75,000-point plate with a 5 mm bore at 0.2 mm spacing
// and a CAD prior slightly off the truth, as a real part is.

#include <cstdint>
#include <vector>

#include "detect/bore/bore_detector.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit::bench {

struct BoreBenchScan {
  sim::SyntheticBoreScan scan;
  BorePrior prior;
};

inline BoreBenchScan make_bore_bench_scan(bool organised) {
  BoreBenchScan x;
  sim::SyntheticBoreOptions o;
  o.radius = 5.0;
  o.extent = 27.4;
  o.spacing = 0.2;
  o.organised = organised;
  o.seed = 7;
  x.scan = sim::make_synthetic_bore(o);
  const auto& t = x.scan.truth;
  x.prior.entrance = t.entrance + Eigen::Vector3d(0.3, -0.2, 0.1);
  x.prior.axis = (t.axis + Eigen::Vector3d(0.03, 0.0, 0.0)).normalized();
  x.prior.radius = 5.0;
  x.prior.plane_normal = t.plane_normal;
  return x;
}

// The region's normal computation as the pipeline runs it: `queries` index the points within
// 2 r (10 mm) of the expected entrance inside `pool`, which adds the 2 mm normal radius.
inline void region_normal_inputs(const std::vector<Eigen::Vector3d>& points,
                                 const Eigen::Vector3d& entrance,
                                 std::vector<Eigen::Vector3d>& pool,
                                 std::vector<std::uint32_t>& queries) {
  for (const auto& p : points) {
    const double d = (p - entrance).norm();
    if (d > 12.0) continue;
    if (d <= 10.0) queries.push_back(static_cast<std::uint32_t>(pool.size()));
    pool.push_back(p);
  }
}

}  // namespace rangefit::bench

namespace rangefit::bench {

// Bore scans at the CSS's real density, the hardest realistic input of the bore detector: the
// CSS's scan circles pass every spot twice, so a part is covered by two interleaved ray grids
// at 0.15-0.17 mm (~70-90 points per mm^2, 40k-90k points per scan, regions up to all of them),
// with the synthetic generator's noise, 5 % outliers and 1 % ghosts. The cost of a pipeline that
// scales with the point count is largest here; the small bore has the fewest wall points (a
// budgeted subset must not lose them) and the large one the largest region and a scan window
// that covers only a strip across it (as a CSS sweep over a 50 mm bore does). d50_60k is the
// hardest realistic case of all: the same bore at the CSS's finest spacing, a ~60,000-point
// region (the largest the CSS scans gave) around a wall seen only as a narrow arc.
struct CssBoreCase {
  const char* name;
  sim::SyntheticBoreOptions scan;
};

inline std::vector<CssBoreCase> css_bore_cases() {
  std::vector<CssBoreCase> c(5);
  const auto base = [](double radius, double spacing, std::uint64_t seed) {
    sim::SyntheticBoreOptions o;
    o.radius = radius;
    o.spacing = spacing;
    o.passes = 2;
    o.march_step = 0.1;
    o.seed = seed;
    o.T_world_part = Eigen::Translation3d(40.0, -25.0, 310.0) *
                     Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 0).normalized());
    return o;
  };
  c[0] = {"d4_blind", base(2.0, 0.15, 41)};
  c[0].scan.depth = 3.0;  // a shallow blind bore: its bottom is in the region
  c[1] = {"d12", base(6.0, 0.15, 42)};
  c[1].scan.extent = 13.0;
  c[2] = {"d25", base(12.5, 0.15, 43)};
  c[2].scan.extent = 14.5;
  c[3] = {"d50", base(25.0, 0.17, 44)};
  c[3].scan.extent = 28.0;
  c[3].scan.extent_v = 12.0;
  c[4] = {"d50_60k", base(25.0, 0.15, 45)};
  c[4].scan.extent = 28.0;
  c[4].scan.extent_v = 11.0;
  return c;
}

// The CAD prior of a case: 0.3 mm and about 1.7 deg off the truth.
inline BorePrior css_prior(const sim::SyntheticBoreTruth& t) {
  BorePrior p;
  p.entrance = t.entrance + Eigen::Vector3d(0.2, -0.2, 0.1);
  p.axis = (t.axis + 0.03 * t.axis.unitOrthogonal()).normalized();
  p.radius = t.radius;
  p.plane_normal = t.plane_normal;
  return p;
}

}  // namespace rangefit::bench
