#pragma once
// The scan both bore benchmarks measure on (bore_benchmark and the optional PCL comparison), so
// that their figures stay comparable: a ~75,000-point plate with a 5 mm bore at 0.2 mm spacing
// and a CAD prior slightly off the truth, as a real part is.

#include <cstdint>
#include <vector>

#include "detect/bore_detector.hpp"
#include "sim/synthetic_bore.hpp"

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
