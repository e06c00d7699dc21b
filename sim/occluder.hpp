#pragma once
// An occluder for a varied scene's target (sim/varied_scene.hpp), sized so that it hides a
// wanted share of the surface the sweep would measure of the target alone: a wall standing next
// to the target on the side of the camera or of the laser (its height found by bisection), or,
// when no wall can hide that much (a camera looking down steeply), an overhang: a plate above the
// target on a leg, reaching across it as far as needed. Neither touches the target.

#include <random>
#include <string>
#include <vector>

#include "sim/scene_objects.hpp"
#include "sim/stripe_sweep.hpp"
#include "sim/visible_surface.hpp"

namespace rangefit::sim {

struct Occluder {
  TableObject object;
  std::string kind;    // "wall" or "overhang"
  double share = 0.0;  // of `samples` hidden by it or already
};

// samples: visible_samples of the target alone on the sweep (non-empty); `already`: those that
// other objects hide. The occluder makes the hidden share `share`.
Occluder make_occluder(const TableObject& target, const std::vector<SurfaceSample>& samples,
                       const std::vector<bool>& already, const StripeSweep& sweep, double share,
                       std::mt19937_64& rng);

}  // namespace rangefit::sim
