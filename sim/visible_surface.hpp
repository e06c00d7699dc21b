#pragma once
// The surface of some parts that a stripe sweep measures, sampled on a coarse grid of its own
// (not the scan's profiles), and the share of it other parts hide. A varied scene places its
// occluder and its clutter with it and reports the occlusion it achieved.

#include <vector>

#include "sim/stripe_scan.hpp"

namespace rangefit::sim {

struct SurfaceSample {
  Eigen::Vector3d point, apex;  // the lit surface point and the laser's apex
  SeenBy cameras;               // the cameras that saw it (of the parts sampled alone)
  // The ray cell (sweep step x fan angle) the sample stands for: a scan has the same number of
  // rays in every such cell, so weighted shares are shares of the scan's points.
  double weight = 1.0;
};

// Casts rays about `spacing_ratio` x the part's bounding radius apart (at the part; at most a
// quarter of its smallest half size) over the bounding sphere of each part listed, through
// `caster`, and keeps the measured hits on that part. within_scan: only sweep positions and fan
// angles the sweep covers; else any (the whole surface the sensor would see from its positions, for
// the share that fell outside the scan).
std::vector<SurfaceSample> visible_samples(const PartCaster& caster, const std::vector<int>& parts,
                                           const StripeSweep& sweep, bool within_scan,
                                           double spacing_ratio = 1.0 / 24.0);

// Per sample: is its laser segment (apex -> point), or the segment to every camera that saw it,
// crossed by a part of `others`.
std::vector<bool> hidden_by(const std::vector<SurfaceSample>& samples, const PartCaster& others);

// Weighted share of `samples` where `mask` is set (0 for no samples).
double weighted_share(const std::vector<SurfaceSample>& samples, const std::vector<bool>& mask);
double total_weight(const std::vector<SurfaceSample>& samples);

}  // namespace rangefit::sim
