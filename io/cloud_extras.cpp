#include "io/cloud_extras.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "io/bounded_reader.hpp"
#include "io/io_error.hpp"

namespace rangefit::io::detail {

namespace {

constexpr std::array<std::pair<SensorView::Kind, std::string_view>, 3> kSensorKinds = {{
    {SensorView::Kind::kPoint, "point"},
    {SensorView::Kind::kLinearSweep, "linear_sweep"},
    {SensorView::Kind::kRotarySweep, "rotary_sweep"},
}};

}  // namespace

std::string format_sensor(const SensorView& v) {
  std::string out;
  for (const auto& [kind, name] : kSensorKinds) {
    if (kind == v.kind) out = std::string(name);
  }
  if (out.empty()) return out;
  char b[40];
  for (const Eigen::Vector3d* x :
       {&v.origin, &v.plane_normal, &v.camera_offset, &v.direction, &v.pivot}) {
    for (int i = 0; i < 3; ++i) {
      std::snprintf(b, sizeof b, " %.17g", (*x)[i]);
      out += b;
    }
  }
  for (double x : {v.sweep_min, v.sweep_max}) {
    std::snprintf(b, sizeof b, " %.17g", x);
    out += b;
  }
  // A second camera follows, so that a file of a one-camera scan reads as it always did.
  if (v.second_camera_offset.squaredNorm() > 0.0) {
    for (int i = 0; i < 3; ++i) {
      std::snprintf(b, sizeof b, " %.17g", v.second_camera_offset[i]);
      out += b;
    }
  }
  return out;
}

std::optional<SensorView> parse_sensor(std::span<const std::string_view> w) {
  if (w.size() != 18 && w.size() != 21) return std::nullopt;
  SensorView v;
  bool known = false;
  for (const auto& [kind, name] : kSensorKinds) {
    if (w[0] == name) v.kind = kind, known = true;
  }
  if (!known) return std::nullopt;
  double x[20];
  for (std::size_t i = 0; i + 1 < w.size(); ++i) {
    if (!parse_double(w[i + 1], x[i]) || !std::isfinite(x[i])) return std::nullopt;
  }
  v.origin = {x[0], x[1], x[2]};
  v.plane_normal = {x[3], x[4], x[5]};
  v.camera_offset = {x[6], x[7], x[8]};
  v.direction = {x[9], x[10], x[11]};
  v.pivot = {x[12], x[13], x[14]};
  v.sweep_min = x[15];
  v.sweep_max = x[16];
  if (w.size() == 21) v.second_camera_offset = {x[17], x[18], x[19]};
  if (!valid(v)) return std::nullopt;
  return v;
}

StampWords split_stamp(std::chrono::nanoseconds stamp) {
  const auto bits = static_cast<std::uint64_t>(stamp.count());
  return {static_cast<std::int32_t>(static_cast<std::uint32_t>(bits >> 32)),
          static_cast<std::uint32_t>(bits & 0xffffffffu)};
}

std::optional<std::chrono::nanoseconds> join_stamp(double hi, double lo) {
  // Range checks first: converting an out-of-range double to an integer is undefined.
  if (!(hi >= -2147483648.0 && hi <= 2147483647.0 && lo >= 0.0 && lo <= 4294967295.0)) {
    return std::nullopt;
  }
  if (hi != std::floor(hi) || lo != std::floor(lo)) return std::nullopt;
  const auto high =
      static_cast<std::uint64_t>(static_cast<std::uint32_t>(static_cast<std::int32_t>(hi)));
  const std::uint64_t bits = (high << 32) | static_cast<std::uint64_t>(lo);
  return std::chrono::nanoseconds(static_cast<std::int64_t>(bits));
}

namespace {

// writable_cells's check of the cloud's arrays and grid.
std::vector<std::int32_t> checked_cells(const std::filesystem::path& file,
                                        const PointCloud& cloud) {
  const std::size_t n = cloud.size();
  if (!cloud.normals.empty() && cloud.normals.size() != n) {
    throw IoError(file, "cannot write: " + std::to_string(cloud.normals.size()) + " normals for " +
                            std::to_string(n) + " points");
  }
  if (!cloud.stamps.empty() && cloud.stamps.size() != n) {
    throw IoError(file, "cannot write: " + std::to_string(cloud.stamps.size()) + " stamps for " +
                            std::to_string(n) + " points");
  }
  if (n > 0x7fffffffu) throw IoError(file, "cannot write: more than 2^31 points");
  if (!cloud.organised()) return {};
  const GridLayout& grid = cloud.grid;
  if (grid.rows < 0 || grid.cols < 0 ||
      grid.index.size() !=
          static_cast<std::size_t>(grid.rows) * static_cast<std::size_t>(grid.cols)) {
    throw IoError(file, "cannot write: grid " + std::to_string(grid.rows) + "x" +
                            std::to_string(grid.cols) + " has " +
                            std::to_string(grid.index.size()) + " cells");
  }
  if (grid.index.size() > 0x7fffffffu) throw IoError(file, "cannot write: grid over 2^31 cells");
  std::vector<std::int32_t> cells(n, -1);
  for (std::size_t cell = 0; cell < grid.index.size(); ++cell) {
    const std::int32_t point = grid.index[cell];
    if (point < -1 || point >= static_cast<std::int64_t>(n)) {
      throw IoError(file, "cannot write: grid cell " + std::to_string(cell) + " refers to point " +
                              std::to_string(point) + " of " + std::to_string(n));
    }
    if (point == -1) continue;
    if (cells[static_cast<std::size_t>(point)] != -1) {
      throw IoError(file, "cannot write: point " + std::to_string(point) + " is in two grid cells");
    }
    cells[static_cast<std::size_t>(point)] = static_cast<std::int32_t>(cell);
  }
  return cells;
}

void check_precision(const std::filesystem::path& file, const PointCloud& cloud,
                     Precision precision) {
  if (precision != Precision::kFloat32) return;
  constexpr double kMax = std::numeric_limits<float>::max();
  auto check = [&](const std::vector<Eigen::Vector3d>& values, const char* what) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      for (int a = 0; a < 3; ++a) {
        const double v = values[i][a];
        if (!std::isfinite(v) || std::abs(v) <= kMax) continue;  // NaN and Inf convert exactly
        throw IoError(file, "cannot write " + std::string(what) + " " + std::to_string(i) +
                                " as float32: beyond its range (write float64)");
      }
    }
  };
  check(cloud.points, "point");
  check(cloud.normals, "normal of point");
}

}  // namespace

std::vector<std::int32_t> writable_cells(const std::filesystem::path& file, const PointCloud& cloud,
                                         Precision precision) {
  std::vector<std::int32_t> cells = checked_cells(file, cloud);
  check_precision(file, cloud, precision);
  if (!cloud.frame_id.empty() && !is_safe_frame_id(cloud.frame_id)) {
    throw IoError(
        file, "cannot write: frame_id " + printable(cloud.frame_id) + " is not one printable word");
  }
  return cells;
}

std::size_t max_grid_cells(std::size_t file_bytes) {
  constexpr std::size_t kFloor = std::size_t{1} << 20;  // 4 MiB of index whatever the file
  return std::max(kFloor, 4 * file_bytes);
}

bool is_safe_frame_id(std::string_view frame_id) {
  if (frame_id.empty() || frame_id.size() > 256) return false;
  for (char c : frame_id) {
    if (c <= ' ' || c >= 0x7f) return false;
  }
  return true;
}

}  // namespace rangefit::io::detail
