#pragma once
// PLY point clouds (Stanford polygon format), as written by CloudCompare, Open3D, PCL, MeshLab.
//
// Reading: ascii, binary_little_endian and binary_big_endian; the vertex element needs x, y, z of
// any scalar type (char..double, also the int8..float64 spellings); nx ny nz (or normal_x ..) are
// read as normals when all three exist. Every other vertex property and every other element
// (faces with list properties, PCL's camera element, ...) is skipped and listed in the report.
// Points with a non-finite position or normal are dropped and counted.
//
// rangefit's extras, which other tools ignore as unknown properties and comments:
//   comment rangefit frame_id <id>      PointCloud::frame_id (default "world" when absent)
//   comment rangefit grid <rows> <cols> organised layout, with the vertex property
//   property int rangefit_cell          row * cols + col of each point, -1 for none
//   property int rangefit_stamp_hi      per-point CLOCK_MONOTONIC stamp in ns, upper 32 bits
//   property uint rangefit_stamp_lo     ... and lower 32 bits
// Positions and normals are written as float by default (what PCL's point types and most viewers
// hold; see cloud_precision.hpp), as double on request (exact round trip). Normals are nx ny nz,
// the Stanford/Open3D/CloudCompare/MeshLab names.

#include <filesystem>

#include "detect/common/point_cloud.hpp"
#include "io/cloud_precision.hpp"
#include "io/cloud_read_report.hpp"
#include "io/io_error.hpp"

namespace rangefit::io {

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// Throws IoError when the file cannot be read or is malformed, truncated or hostile.
PointCloud read_ply(const std::filesystem::path& path, CloudReadReport* report = nullptr);

// Throws IoError when the cloud is inconsistent (see detail::writable_cells), holds a value float
// cannot (kFloat32) or on write failure.
void write_ply(const std::filesystem::path& path, const PointCloud& cloud,
               PlyEncoding encoding = PlyEncoding::kBinaryLittleEndian,
               Precision precision = Precision::kFloat32);

}  // namespace rangefit::io
