#pragma once
// The point-cloud value type shared by every stage: fusion produces it, detect consumes it, io
// reads and writes it. A struct of vectors, copied and moved like any value.

#include <Eigen/Core>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "detect/common/sensor_view.hpp"

namespace rangefit {

// Organised layout of a scan, e.g. revolution x sample for the CSS (512 columns) or profile x
// point for the stripe sensor. index[r * cols + c] is the point index of that cell, or -1 when
// the cell has no valid sample. Lets detect/ find neighbours by grid position instead of a tree.
struct GridLayout {
  int rows = 0;
  int cols = 0;
  std::vector<std::int32_t> index;

  bool empty() const { return rows == 0 || cols == 0; }
  std::int32_t at(int r, int c) const { return index[static_cast<std::size_t>(r) * cols + c]; }
};

struct PointCloud {
  std::string frame_id = "world";                // frame the positions are expressed in
  std::vector<Eigen::Vector3d> points;           // positions, mm
  std::vector<Eigen::Vector3d> normals;          // empty, or one unit vector per point
  std::vector<std::chrono::nanoseconds> stamps;  // empty, or CLOCK_MONOTONIC time per point
  GridLayout grid;                               // empty when the cloud is unorganised
  SensorView sensor;                             // how the scan was taken (kUnknown: not known)

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_normals() const { return !normals.empty() && normals.size() == points.size(); }
  bool has_stamps() const { return !stamps.empty() && stamps.size() == points.size(); }
  bool organised() const { return !grid.empty(); }
};

// Appends `view`'s points to `fused` (views in one frame): normals and stamps while every view
// has them. The result is unorganised, and its sensor is unknown until the caller says (the
// views' own sensors may differ).
inline void append_view(PointCloud& fused, const PointCloud& view) {
  const bool first = fused.points.empty();
  const bool normals = view.has_normals() && (first || fused.has_normals());
  const bool stamps = view.has_stamps() && (first || fused.has_stamps());
  fused.points.insert(fused.points.end(), view.points.begin(), view.points.end());
  if (normals) {
    fused.normals.insert(fused.normals.end(), view.normals.begin(), view.normals.end());
  } else {
    fused.normals.clear();
  }
  if (stamps) {
    fused.stamps.insert(fused.stamps.end(), view.stamps.begin(), view.stamps.end());
  } else {
    fused.stamps.clear();
  }
  fused.grid = {};
  fused.sensor = {};
}

}  // namespace rangefit
