#pragma once
// The object of a teach-in scan (thesis ch. 6: "show the object once"): the dominant plane
// (the table, thesis 5.1.1) is removed and the rest split into Euclidean clusters (points
// closer than a gap chained together); the object is the largest cluster, or the one whose
// centroid is nearest a given point.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "detect/common/plane_removal.hpp"

namespace rangefit {

struct SegmentOptions {
  bool remove_plane = true;
  PlaneRemovalOptions plane;
  // Points closer than this are one object; 0: four times the scan's sample spacing (the larger
  // of the median nearest-neighbour distance and the spacing the 16 nearest imply).
  double gap_mm = 0.0;
  std::size_t min_points = 50;          // smaller clusters are noise
  std::optional<Eigen::Vector3d> near;  // pick the cluster nearest this point (else the largest)
  // Keep this many clusters, best first (a two-part object whose parts do not touch, e.g. a
  // mallet whose shaft model ends short of the head, is two clusters).
  int keep = 1;
};

struct SegmentResult {
  PlaneRemovalResult plane;
  std::vector<std::uint32_t> object;  // indices into the points, ascending; empty: no object
  // The kept clusters (object is their union), best first, each ascending.
  std::vector<std::vector<std::uint32_t>> kept;
  std::size_t clusters = 0;  // clusters of at least min_points
  double gap_mm = 0.0;       // the gap used
};

SegmentResult segment_object(std::span<const Eigen::Vector3d> points,
                             const SegmentOptions& options = {});

}  // namespace rangefit
