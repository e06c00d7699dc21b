#pragma once
// Dominant plane removal (thesis 5.1.1): the table under a single-view scene holds most points,
// slows the object search and invites false fits, so it is found and removed first. The plane is
// reported as well: the robot uses it as a reference.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "detect/common/pca.hpp"

namespace rangefit {

struct PlaneRemovalOptions {
  int seeds = 100;                     // plane patch seeds, spread evenly over the cloud
  std::size_t subsample = 4000;        // points the patches and the support are computed on
  int patch_points = 16;               // nearest subsample points of each seed in its PCA patch
  double distance_tolerance_mm = 2.0;  // a point within this of the plane belongs to it
  double noise_factor = 4.0;           // ... or within this many times the plane's rms
  std::uint64_t seed = 1;              // offset of the even spread
  int threads = 0;                     // the seeds' patches on this many threads (0: all cores);
                                       // the same plane on any number
};

enum class PlaneRemovalReason {
  kRemoved,       // the dominant plane held more points than the rest and was removed
  kNotDominant,   // the best plane held fewer points than the rest: nothing removed
  kTooFewPoints,  // fewer than patch_points points: nothing removed
};

struct PlaneRemovalResult {
  PlaneRemovalReason reason = PlaneRemovalReason::kTooFewPoints;
  pca::Plane plane;                      // the best plane found (valid() even when not removed)
  std::size_t plane_points = 0;          // points of the full cloud within the tolerance (the
                                         // larger of distance_tolerance_mm and noise_factor rms)
  std::vector<std::uint32_t> remaining;  // indices of the points kept, ascending
  bool removed() const { return reason == PlaneRemovalReason::kRemoved; }
};

PlaneRemovalResult remove_dominant_plane(std::span<const Eigen::Vector3d> points,
                                         const PlaneRemovalOptions& options = {});

}  // namespace rangefit
