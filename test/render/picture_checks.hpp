#pragma once
// What the render tests share: the clean synthetic bore they draw, and the pixel check that a
// colour is drawn near a projected point.

#include <Eigen/Core>
#include <cmath>
#include <cstdlib>

#include "render/image.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit::render::test {

inline bool near_colour(Rgb a, Rgb b, int tolerance) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
         std::abs(a.b - b.b) <= tolerance;
}

// The colour within `radius` px of pixel p (antialiased 1.5 px lines may straddle two pixels).
inline bool colour_near(const Image& image, const Eigen::Vector2d& p, Rgb colour, int radius = 1,
                        int tolerance = 30) {
  const int cx = static_cast<int>(std::floor(p.x())), cy = static_cast<int>(std::floor(p.y()));
  for (int y = cy - radius; y <= cy + radius; ++y) {
    for (int x = cx - radius; x <= cx + radius; ++x) {
      if (image.contains(x, y) && near_colour(image.at(x, y), colour, tolerance)) return true;
    }
  }
  return false;
}

// A 5 mm bore without outliers or ghosts, 0.3 mm spacing.
inline sim::SyntheticBoreScan clean_bore() {
  sim::SyntheticBoreOptions o;
  o.radius = 5.0;
  o.outlier_fraction = 0.0;
  o.ghost_fraction = 0.0;
  o.spacing = 0.3;
  return sim::make_synthetic_bore(o);
}

}  // namespace rangefit::render::test
