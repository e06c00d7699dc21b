// The distance model learning fits and reports (detect/learn/learn_surface.hpp): a point moved
// off a part's surface along the normal reads as that move, on untapered and tapered parts, near
// a pyramid's tip too, where the radial distance reads it many times over.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "detect/learn/learn_surface.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit {
namespace learn_surface_test {

// The outward unit normal at a surface point, from the metric's gradient there.
Eigen::Vector3d normal_at(const SuperquadricMetric& m, const Eigen::Vector3d& p) {
  Eigen::Vector3d grad;
  m.value_and_gradient(p, grad);
  return grad.normalized();
}

struct Worst {
  double distance = 0.0, radial = 0.0;  // largest |read - moved| / moved
};

// Surface points over the part (latitudes off the poles, eq. 2.14), each moved `by` mm along its
// normal outwards and inwards.
Worst read_moves(const Superquadric& sq, double by) {
  const SuperquadricMetric m(sq);
  Worst w;
  const double pi = std::numbers::pi;
  for (int i = 1; i < 12; ++i) {
    for (int j = 0; j < 16; ++j) {
      const Eigen::Vector3d s = surface_point(sq, -pi / 2 + pi * i / 12.0, -pi + 2 * pi * j / 16.0);
      const Eigen::Vector3d n = normal_at(m, s);
      for (double sign : {1.0, -1.0}) {
        const Eigen::Vector3d q = s + sign * by * n;
        const double d = radial_surface_distance(m, q);
        const double f = radial_distance(m.value(q), q.norm());
        w.distance = std::max(w.distance, std::abs(d - sign * by) / by);
        w.radial = std::max(w.radial, std::abs(f - sign * by) / by);
      }
    }
  }
  return w;
}

TEST(LearnSurface, APointMovedAlongTheNormalReadsAsTheMove) {
  // A ball, a rounded box and a tapered cup, each moved 0.05 mm: the scan's noise.
  const Superquadric ball{25, 25, 25, 1.0, 1.0, 0.0, 0.0};
  const Superquadric box{15, 25, 35, 0.3, 0.3, 0.0, 0.0};
  const Superquadric cup{34, 34, 68, 0.3, 1.0, 0.2, 0.2};
  for (const Superquadric& sq : {ball, box, cup}) {
    EXPECT_LT(read_moves(sq, 0.05).distance, 0.05) << sq.a1 << " " << sq.eps1 << " " << sq.kx;
  }
}

TEST(LearnSurface, NearAPyramidsTipTheDistanceIsNotInflated) {
  // Table 5.6's pyramid: 30 mm base, 1.6 mm tip, 44 mm tall.
  const Superquadric pyramid{8, 8, 22, 0.5, 0.5, -0.9, -0.9};
  const Worst w = read_moves(pyramid, 0.05);
  EXPECT_LT(w.distance, 0.2) << w.radial;
  // What the fits read before: the radial distance overstates some moves several times.
  EXPECT_GT(w.radial, 2.0);
}

}  // namespace learn_surface_test
}  // namespace rangefit
