// Random vectors drawn in a stated order. The arguments of a call are evaluated in an unspecified
// order (GCC right to left, clang left to right), so `Vector3d(u(rng), u(rng), u(rng))` is another
// vector under each compiler and a seed no longer names one input. draw3 draws z, then y, then x:
// the order in which the tests' recorded data were made (by GCC).
#pragma once

#include <Eigen/Core>

namespace rangefit::test {

template <class Distribution, class Engine>
Eigen::Vector3d draw3(Distribution& d, Engine& rng) {
  const double z = d(rng);
  const double y = d(rng);
  const double x = d(rng);
  return {x, y, z};
}

}  // namespace rangefit::test
