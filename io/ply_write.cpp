// PLY writer: float (or double) positions and normals, rangefit extras as documented in ply.hpp.

#include <string>

#include "io/bounded_reader.hpp"
#include "io/cloud_extras.hpp"
#include "io/ply.hpp"
#include "io/scalar.hpp"
#include "io/text_number.hpp"

namespace rangefit::io {

void write_ply(const std::filesystem::path& path, const PointCloud& cloud, PlyEncoding encoding,
               Precision precision) {
  const std::vector<std::int32_t> cells = detail::writable_cells(path, cloud, precision);
  const bool normals = cloud.has_normals();
  const bool stamps = cloud.has_stamps();
  const bool grid = cloud.organised();

  std::string out = "ply\nformat ";
  out += encoding == PlyEncoding::kAscii                ? "ascii"
         : encoding == PlyEncoding::kBinaryLittleEndian ? "binary_little_endian"
                                                        : "binary_big_endian";
  out += " 1.0\ncomment written by rangefit, units mm\n";
  if (!cloud.frame_id.empty()) out += "comment rangefit frame_id " + cloud.frame_id + "\n";
  if (const std::string sensor = detail::format_sensor(cloud.sensor); !sensor.empty()) {
    out += "comment rangefit sensor " + sensor + "\n";
  }
  if (grid) {
    out += "comment rangefit grid " + std::to_string(cloud.grid.rows) + " " +
           std::to_string(cloud.grid.cols) + "\n";
  }
  out += "element vertex " + std::to_string(cloud.size()) + "\n";
  const bool f32 = precision == Precision::kFloat32;
  const std::string real = f32 ? "property float " : "property double ";
  out += real + "x\n" + real + "y\n" + real + "z\n";
  if (normals) out += real + "nx\n" + real + "ny\n" + real + "nz\n";
  if (stamps) {
    out += "property int " + std::string(detail::kStampHi) + "\nproperty uint " +
           std::string(detail::kStampLo) + "\n";
  }
  if (grid) out += "property int " + std::string(detail::kCell) + "\n";
  out += "end_header\n";

  const bool ascii = encoding == PlyEncoding::kAscii;
  const bool big = encoding == PlyEncoding::kBinaryBigEndian;
  out.reserve(out.size() + cloud.size() * (ascii ? 80 : 60));
  auto put_double = [&](double value, bool last) {
    if (f32) {
      const auto single = static_cast<float>(value);  // in range: writable_cells
      if (!ascii) return detail::append_raw(out, single, big);
      detail::append_number(out, single);
    } else {
      if (!ascii) return detail::append_raw(out, value, big);
      detail::append_number(out, value);
    }
    out += last ? '\n' : ' ';
  };
  auto put_int = [&](std::int64_t value, bool last) {
    detail::append_number(out, value);
    out += last ? '\n' : ' ';
  };
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    put_double(p.x(), false);
    put_double(p.y(), false);
    put_double(p.z(), !normals && !stamps && !grid);
    if (normals) {
      const Eigen::Vector3d& n = cloud.normals[i];
      put_double(n.x(), false);
      put_double(n.y(), false);
      put_double(n.z(), !stamps && !grid);
    }
    if (stamps) {
      const detail::StampWords words = detail::split_stamp(cloud.stamps[i]);
      if (ascii) {
        put_int(words.hi, false);
        put_int(words.lo, !grid);
      } else {
        detail::append_raw(out, words.hi, big);
        detail::append_raw(out, words.lo, big);
      }
    }
    if (grid) {
      const std::int32_t cell = cells.empty() ? -1 : cells[i];
      if (ascii) {
        put_int(cell, true);
      } else {
        detail::append_raw(out, cell, big);
      }
    }
  }
  detail::save_file(path, out);
}

}  // namespace rangefit::io
