#pragma once
// Point-cloud files by extension: .ply or .pcd (any case), or "-" for stdin/stdout. The format
// details, rangefit's extras and the error contract are those of ply.hpp and pcd.hpp.

#include <filesystem>
#include <optional>

#include "detect/common/point_cloud.hpp"
#include "io/cloud_precision.hpp"
#include "io/cloud_read_report.hpp"
#include "io/io_error.hpp"

namespace rangefit::io {

enum class CloudFormat { kPly, kPcd };

// The path a command line names standard input or output with.
inline bool is_stdio(const std::filesystem::path& path) { return path == "-"; }

// Throws IoError for an unknown extension, or whatever the format's reader throws. "-" reads
// standard input to its end; PLY or PCD is told by its first line, and errors name "stdin".
PointCloud read_cloud(const std::filesystem::path& path, CloudReadReport* report = nullptr);

// Writes binary PLY or binary PCD by `format`, or when unset by the extension; "-" writes
// standard output (binary PLY unless `format` says PCD). Throws IoError for an unknown extension
// or what the format's writer throws.
void write_cloud(const std::filesystem::path& path, const PointCloud& cloud,
                 Precision precision = Precision::kFloat32,
                 std::optional<CloudFormat> format = std::nullopt);

}  // namespace rangefit::io
