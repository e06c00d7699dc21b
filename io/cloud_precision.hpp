#pragma once
// Scalar type the PLY and PCD writers store positions and normals in.

namespace rangefit::io {

// kFloat32 is the default because other tools' point types are float: PCL's pcl::PointXYZ and
// PointNormal (loadPCDFile/loadPLYFile find no match for a double x and leave it zero), ROS
// PointCloud2 consumers, most viewers. At scan sizes (a few metres in mm) float keeps about
// 0.1 um. kFloat64 round-trips a cloud exactly, for files rangefit itself re-reads (spooled scans
// that a replay must reproduce bit for bit).
enum class Precision { kFloat32, kFloat64 };

}  // namespace rangefit::io
