#pragma once
// PCD point clouds (Point Cloud Library, v0.6/v0.7), as written by PCL, Open3D and CloudCompare.
//
// Reading: DATA ascii, binary and binary_compressed (LZF, fields stored one after another); x, y,
// z of any TYPE/SIZE (F 4/8, I and U 1/2/4/8) are required; normal_x/normal_y/normal_z become
// normals. Other fields (rgb, curvature, intensity, PCL's "_" padding, ...) are skipped and listed
// in the report (padding excepted). An organised file (HEIGHT > 1) fills PointCloud::grid with
// rows = HEIGHT and cols = WIDTH; NaN/Inf points are dropped, counted and their cells set to -1.
//
// Writing: x y z (and normal_x normal_y normal_z) as F 4 by default, the layout of PCL's
// PointXYZ/PointNormal (see cloud_precision.hpp), or F 8 on request (exact round trip). rangefit's
// extras are fields other tools ignore: rangefit_stamp_hi (I 4) and rangefit_stamp_lo (U 4) hold
// the stamp in ns, and a "# rangefit frame_id <id>" comment line the frame. An organised cloud is
// written as WIDTH = cols, HEIGHT = rows with NaN in empty cells, so each of its points must sit in
// a grid cell, and it reads back with its points in row-major cell order.

#include <filesystem>

#include "detect/common/point_cloud.hpp"
#include "io/cloud_precision.hpp"
#include "io/cloud_read_report.hpp"
#include "io/io_error.hpp"

namespace rangefit::io {

enum class PcdEncoding { kAscii, kBinary };

// Throws IoError when the file cannot be read or is malformed, truncated or hostile.
PointCloud read_pcd(const std::filesystem::path& path, CloudReadReport* report = nullptr);

// Throws IoError when the cloud is inconsistent (sizes, grid), holds a value float cannot
// (kFloat32) or on write failure.
void write_pcd(const std::filesystem::path& path, const PointCloud& cloud,
               PcdEncoding encoding = PcdEncoding::kBinary,
               Precision precision = Precision::kFloat32);

}  // namespace rangefit::io
