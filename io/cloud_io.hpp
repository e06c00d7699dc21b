#pragma once
// Point-cloud files by extension: .ply or .pcd (any case). The format details, rangefit's extras
// and the error contract are those of ply.hpp and pcd.hpp.

#include <filesystem>

#include "detect/point_cloud.hpp"
#include "io/cloud_read_report.hpp"
#include "io/io_error.hpp"

namespace rangefit::io {

// Throws IoError for an unknown extension, or whatever the format's reader throws.
PointCloud read_cloud(const std::filesystem::path& path, CloudReadReport* report = nullptr);

// Writes binary PLY or binary PCD by extension; throws IoError for an unknown extension.
void write_cloud(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace rangefit::io
