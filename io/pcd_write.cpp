// PCD writer: F 4 (or F 8) positions and normals, stamp words, organised layout as WIDTH x HEIGHT.

#include <limits>
#include <string>

#include "io/bounded_reader.hpp"
#include "io/cloud_extras.hpp"
#include "io/pcd.hpp"
#include "io/scalar.hpp"
#include "io/text_number.hpp"

namespace rangefit::io {

void write_pcd(const std::filesystem::path& path, const PointCloud& cloud, PcdEncoding encoding,
               Precision precision) {
  const std::vector<std::int32_t> cells = detail::writable_cells(path, cloud, precision);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (cells[i] < 0) {
      throw IoError(path, "cannot write: point " + std::to_string(i) +
                              " is in no grid cell, an organised PCD cannot hold it");
    }
  }
  const bool normals = cloud.has_normals();
  const bool stamps = cloud.has_stamps();
  const bool organised = cloud.organised();
  const std::size_t width = organised ? static_cast<std::size_t>(cloud.grid.cols) : cloud.size();
  const std::size_t height = organised ? static_cast<std::size_t>(cloud.grid.rows) : 1;

  const bool f32 = precision == Precision::kFloat32;
  const std::string real_sizes = f32 ? "4 4 4" : "8 8 8";
  std::string fields = "x y z", sizes = real_sizes, types = "F F F", counts = "1 1 1";
  if (normals) {
    fields += " normal_x normal_y normal_z";
    sizes += " " + real_sizes;
    types += " F F F";
    counts += " 1 1 1";
  }
  if (stamps) {
    fields += " " + std::string(detail::kStampHi) + " " + std::string(detail::kStampLo);
    sizes += " 4 4";
    types += " I U";
    counts += " 1 1";
  }
  const bool ascii = encoding == PcdEncoding::kAscii;
  std::string out = "# .PCD v0.7 - Point Cloud Data file format (written by rangefit, units mm)\n";
  if (!cloud.frame_id.empty()) out += "# rangefit frame_id " + cloud.frame_id + "\n";
  if (const std::string sensor = detail::format_sensor(cloud.sensor); !sensor.empty()) {
    out += "# rangefit sensor " + sensor + "\n";
  }
  out += "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types + "\nCOUNT " +
         counts + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " + std::to_string(height) +
         "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(width * height) + "\nDATA " +
         (ascii ? "ascii" : "binary") + "\n";

  const std::size_t total = width * height;
  out.reserve(out.size() + total * (ascii ? 80 : 56));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto put = [&](double value) {
    if (f32) {
      const auto single = static_cast<float>(value);  // in range: writable_cells
      if (!ascii) return detail::append_raw(out, single, false);
      detail::append_number(out, single);  // "nan" for empty cells, as PCL writes them
    } else {
      if (!ascii) return detail::append_raw(out, value, false);
      detail::append_number(out, value);
    }
    out += ' ';
  };
  for (std::size_t k = 0; k < total; ++k) {
    const std::int32_t i = organised ? cloud.grid.index[k] : static_cast<std::int32_t>(k);
    const bool valid = i >= 0;
    const auto at = static_cast<std::size_t>(valid ? i : 0);
    for (int a = 0; a < 3; ++a) put(valid ? cloud.points[at][a] : nan);
    if (normals) {
      for (int a = 0; a < 3; ++a) put(valid ? cloud.normals[at][a] : nan);
    }
    if (stamps) {
      const detail::StampWords words =
          valid ? detail::split_stamp(cloud.stamps[at]) : detail::StampWords{};
      if (ascii) {
        detail::append_number(out, std::int64_t{words.hi});
        out += ' ';
        detail::append_number(out, std::int64_t{words.lo});
        out += ' ';
      } else {
        detail::append_raw(out, words.hi, false);
        detail::append_raw(out, words.lo, false);
      }
    }
    if (ascii) out.back() = '\n';
  }
  detail::save_file(path, out);
}

}  // namespace rangefit::io
