#pragma once
// The six planes of the calibration cube in one scan (thesis 3.2.3): RANSAC that only admits
// points whose surface normal (PCA of a patch) points about the way of the plane it looks for,
// after which the plane is refitted by least squares and its points are removed before the next
// one. Each cube direction gets two planes, the outer face and the far bars' inner face; the one
// nearer the sensor along the normal is the outer one.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "calib/calibration_cube.hpp"

namespace rangefit::calib {

struct PlaneExtractionOptions {
  double max_normal_angle_rad = 0.26;  // ~15 deg: the rough start is off by up to a few degrees
  double inlier_distance_mm = 1.0;     // RANSAC and final support
  int iterations = 200;                // RANSAC samples per plane
  std::size_t min_points = 30;         // fewer: the plane is missing
  std::uint64_t seed = 1;
};

struct ExtractedPlane {
  bool found = false;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, same side as the expected plane
  double offset_mm = 0.0;                             // normal . x = offset
  double rms_mm = 0.0;
  std::vector<std::uint32_t> inliers;  // indices into the points
};

// expected: the six planes (visible_planes order) roughly where they should be; normals: one per
// point, zero where none. Result in the same order.
std::array<ExtractedPlane, 6> extract_cube_planes(std::span<const Eigen::Vector3d> points,
                                                  std::span<const Eigen::Vector3d> normals,
                                                  const std::array<CubePlane, 6>& expected,
                                                  const PlaneExtractionOptions& options);

}  // namespace rangefit::calib
