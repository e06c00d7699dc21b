#pragma once
// rangefit's own per-point data in files other tools also read: stamps split into two 32-bit
// integers (PLY has no 64-bit type, and this keeps PLY and PCD alike) and the organised layout.
// Shared by the PLY and PCD codecs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "detect/common/point_cloud.hpp"
#include "io/cloud_precision.hpp"

namespace rangefit::io::detail {

inline constexpr std::string_view kStampHi = "rangefit_stamp_hi";  // int32: stamp_ns >> 32
inline constexpr std::string_view kStampLo = "rangefit_stamp_lo";  // uint32: stamp_ns & 0xffffffff
inline constexpr std::string_view kCell = "rangefit_cell";         // int32: row * cols + col, or -1

struct StampWords {
  std::int32_t hi = 0;
  std::uint32_t lo = 0;
};
StampWords split_stamp(std::chrono::nanoseconds stamp);
// nullopt when the words are not integers in their types' ranges.
std::optional<std::chrono::nanoseconds> join_stamp(double hi, double lo);

// Checks that a cloud handed to a writer can be written at `precision`; throws IoError naming
// `file` otherwise:
// - it is consistent: normals and stamps sized like the points, grid cells within range and each
//   point in at most one cell;
// - with kFloat32, no finite coordinate or normal component is beyond float's range (converting
//   it would be undefined, not infinite);
// - its frame id, if any, is one printable word (is_safe_frame_id).
// Returns the cell of each point (-1 when it is in none), empty for an unorganised cloud.
std::vector<std::int32_t> writable_cells(const std::filesystem::path& file, const PointCloud& cloud,
                                         Precision precision);

// Largest grid a file of `file_bytes` may declare: the index is allocated before the points are
// read, so it is bounded by the file size (with a floor for sparse scans in small files).
std::size_t max_grid_cells(std::size_t file_bytes);

// The scan's SensorView as the words of a header comment after "rangefit sensor": the kind
// (point, linear_sweep, rotary_sweep) and 17 numbers (origin, plane normal, camera offset,
// direction, pivot, sweep min and max), then 3 more with a second camera (its offset). Empty for
// an unknown sensor.
std::string format_sensor(const SensorView& view);
// From the words after "sensor"; nullopt when they are not a valid SensorView.
std::optional<SensorView> parse_sensor(std::span<const std::string_view> words);

// A frame id is written on a header line, so it must be one printable word.
bool is_safe_frame_id(std::string_view frame_id);

}  // namespace rangefit::io::detail
