#pragma once
// The first returns of a single-view scan as seen from its viewpoint: a pinhole image around the
// mean viewing direction whose pixels hold the smallest range of the points in them. It answers
// "what did the sensor see along the ray to this point?": something in front of it, something at
// it, or only things behind it. The last is free space: a surface claimed there would have hidden
// what the sensor saw, so it is not there (beyond the thesis, used to confirm detections).

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace rangefit {

enum class RayEvidence {
  kUnknown,  // no return in this direction (outside the scan, or nothing reflected)
  kInFront,  // the first return is nearer: the point may be occluded
  kAt,       // the first return is within the tolerance of the point
  kBehind,   // every return is farther: the sensor saw past the point
};

class RangeImage {
 public:
  // Points (world frame, mm) and the sensor position; pixels are sized for about
  // `points_per_pixel` points each (larger pixels: fewer empty ones, coarser edges).
  RangeImage(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& viewpoint,
             double points_per_pixel = 4.0);
  // What the sensor saw along the ray to p: the nearest return in p's pixel and its 8 neighbours
  // (so a point at a silhouette, whose own pixel may hold only background, is not seen past).
  RayEvidence along(const Eigen::Vector3d& p, double tolerance_mm) const;
  bool empty() const { return ranges_.empty(); }

 private:
  // Pixel (column, row) of a direction; false outside the image (or behind the viewpoint).
  bool pixel(const Eigen::Vector3d& d, std::ptrdiff_t* col, std::ptrdiff_t* row) const;

  Eigen::Vector3d viewpoint_;
  Eigen::Matrix3d to_view_ = Eigen::Matrix3d::Identity();  // rows: image u, image v, view axis
  double u0_ = 0.0, v0_ = 0.0, inv_cell_ = 1.0;
  std::ptrdiff_t nu_ = 0, nv_ = 0;
  std::vector<float> ranges_;  // smallest range per pixel, mm; +inf when empty
};

}  // namespace rangefit
