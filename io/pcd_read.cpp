// PCD reader: header, count checks against the data size, then values by field and point from
// whichever layout the DATA line names.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "io/bounded_reader.hpp"
#include "io/cloud_extras.hpp"
#include "io/lzf.hpp"
#include "io/pcd.hpp"
#include "io/scalar.hpp"

namespace rangefit::io {
namespace {

using detail::BoundedReader;
using detail::printable;
using detail::Scalar;

// binary_compressed data may expand by LZF's worst case (88x), so a 3 MB file could make us
// allocate 270 MB; no scan comes near this absolute bound (16 M points of x y z floats).
constexpr std::uint64_t kMaxUncompressedBytes = std::uint64_t{256} << 20;
constexpr std::uint64_t kMaxFieldCount = 1u << 16;  // PCL's widest descriptors have a few hundred

enum class Data { kAscii, kBinary, kBinaryCompressed };

struct Field {
  std::string name;
  Scalar type = Scalar::kFloat32;
  std::size_t size = 4;
  std::size_t count = 1;
  std::size_t offset = 0;  // bytes before this field in one point (binary), or in the layout
};

struct PcdHeader {
  std::vector<Field> fields;
  std::uint64_t width = 0;
  std::uint64_t height = 1;
  std::uint64_t points = 0;
  std::uint64_t stride = 0;  // bytes per point
  std::uint64_t values = 0;  // numbers per point
  Data data = Data::kAscii;
  std::string frame_id = "world";
  SensorView sensor;
};

std::uint64_t parse_count(BoundedReader& r, std::string_view key, std::string_view token) {
  std::int64_t value = 0;
  if (!detail::parse_int64(token, value) || value < 0) {
    r.fail_at_line("header: " + std::string(key) + " " + printable(token) +
                   " is not a non-negative integer");
  }
  return static_cast<std::uint64_t>(value);
}

std::optional<Scalar> pcd_scalar(char type, std::size_t size) {
  if (type == 'F') {
    if (size == 4) return Scalar::kFloat32;
    if (size == 8) return Scalar::kFloat64;
  } else if (type == 'I' || type == 'U') {
    const bool u = type == 'U';
    if (size == 1) return u ? Scalar::kUint8 : Scalar::kInt8;
    if (size == 2) return u ? Scalar::kUint16 : Scalar::kInt16;
    if (size == 4) return u ? Scalar::kUint32 : Scalar::kInt32;
    if (size == 8) return u ? Scalar::kUint64 : Scalar::kInt64;
  }
  return std::nullopt;
}

PcdHeader parse_pcd_header(BoundedReader& r) {
  PcdHeader h;
  std::vector<std::string_view> names, sizes, types, counts;
  std::optional<std::uint64_t> points;
  bool have_width = false;
  bool have_data = false;
  while (!have_data) {
    const auto line = r.next_line();
    if (!line) r.fail("header: truncated, no DATA line");
    const auto w = detail::split_words(*line);
    if (w.empty()) continue;
    if (w[0].front() == '#') {
      if (w.size() == 4 && w[1] == "rangefit" && w[2] == "frame_id") h.frame_id = std::string(w[3]);
      if (w.size() >= 3 && w[1] == "rangefit" && w[2] == "sensor") {
        const std::optional<SensorView> v =
            detail::parse_sensor(std::span<const std::string_view>(w).subspan(3));
        if (!v) r.fail_at_line("header: 'rangefit sensor' is not a kind and 17 finite numbers");
        h.sensor = *v;
      }
      continue;
    }
    const std::vector<std::string_view> args(w.begin() + 1, w.end());
    if (w[0] == "VERSION" || w[0] == "VIEWPOINT") {
      // VIEWPOINT is the acquisition pose; rangefit clouds carry their frame instead.
    } else if (w[0] == "FIELDS" || w[0] == "COLUMNS") {
      names = args;
    } else if (w[0] == "SIZE") {
      sizes = args;
    } else if (w[0] == "TYPE") {
      types = args;
    } else if (w[0] == "COUNT") {
      counts = args;
    } else if (w[0] == "WIDTH" || w[0] == "HEIGHT" || w[0] == "POINTS") {
      if (args.size() != 1) r.fail_at_line("header: " + std::string(w[0]) + " needs one value");
      const std::uint64_t value = parse_count(r, w[0], args[0]);
      if (w[0] == "WIDTH") {
        h.width = value;
        have_width = true;
      } else if (w[0] == "HEIGHT") {
        h.height = value;
      } else {
        points = value;
      }
    } else if (w[0] == "DATA") {
      if (args.size() != 1) r.fail_at_line("header: DATA needs one value");
      if (args[0] == "ascii") {
        h.data = Data::kAscii;
      } else if (args[0] == "binary") {
        h.data = Data::kBinary;
      } else if (args[0] == "binary_compressed") {
        h.data = Data::kBinaryCompressed;
      } else {
        r.fail_at_line("header: unknown DATA " + printable(args[0]));
      }
      have_data = true;
    } else {
      r.fail_at_line("header: unknown keyword " + printable(w[0]));
    }
  }
  if (names.empty()) r.fail("header: no FIELDS line");
  if (sizes.size() != names.size() || types.size() != names.size()) {
    r.fail("header: " + std::to_string(names.size()) + " FIELDS but " +
           std::to_string(sizes.size()) + " SIZE and " + std::to_string(types.size()) +
           " TYPE entries");
  }
  if (!counts.empty() && counts.size() != names.size()) {
    r.fail("header: " + std::to_string(names.size()) + " FIELDS but " +
           std::to_string(counts.size()) + " COUNT entries");
  }
  if (!have_width) r.fail("header: no WIDTH line");
  for (std::size_t i = 0; i < names.size(); ++i) {
    Field f;
    f.name = std::string(names[i]);
    const std::uint64_t size = parse_count(r, "SIZE", sizes[i]);
    const auto type = types[i].size() == 1 ? pcd_scalar(types[i][0], size) : std::nullopt;
    if (!type) {
      r.fail("header: field " + printable(names[i]) + " has unsupported TYPE " +
             printable(types[i]) + " with SIZE " + printable(sizes[i]));
    }
    f.type = *type;
    f.size = static_cast<std::size_t>(size);
    f.count = counts.empty() ? 1 : parse_count(r, "COUNT", counts[i]);
    if (f.count == 0 || f.count > kMaxFieldCount) {
      r.fail("header: field " + printable(names[i]) + " COUNT " + std::to_string(f.count) +
             " is out of range 1.." + std::to_string(kMaxFieldCount));
    }
    f.offset = h.stride;
    h.stride += f.size * f.count;
    h.values += f.count;
    h.fields.push_back(std::move(f));
  }
  if (h.height != 0 && h.width > UINT64_MAX / h.height) r.fail("header: WIDTH x HEIGHT overflows");
  if (points && *points != h.width * h.height) {
    r.fail("header: POINTS " + std::to_string(*points) + " is not WIDTH " +
           std::to_string(h.width) + " x HEIGHT " + std::to_string(h.height));
  }
  h.points = h.width * h.height;
  return h;
}

int find(const PcdHeader& h, std::string_view name) {
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    if (h.fields[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

// The point data as one value per (point, field), whatever the DATA layout.
class Values {
 public:
  Values(BoundedReader& r, const PcdHeader& h) : r_(r), h_(h) {
    const std::uint64_t budget = r.remaining();
    if (h.data == Data::kAscii) {
      // Each value is a number and a separator: two bytes at least (the last may lack one).
      if (h.points > 0 && h.points > (budget + 1) / (2 * h.values)) too_many(budget);
    } else if (h.data == Data::kBinary) {
      if (h.points > budget / h.stride) too_many(budget);
      block_ = r.take(h.points * h.stride, "binary data");
    } else {
      decompress();
    }
  }

  // Reads the next point's values (ascii) or positions on point i (binary layouts).
  void next_point(std::uint64_t i, std::vector<double>& first_values) {
    first_values.resize(h_.fields.size());
    for (std::size_t f = 0; f < h_.fields.size(); ++f) {
      const Field& field = h_.fields[f];
      if (h_.data == Data::kAscii) {
        for (std::size_t k = 0; k < field.count; ++k) {
          const double value = ascii_value(i);
          if (k == 0) first_values[f] = value;
        }
        continue;
      }
      const std::size_t at = h_.data == Data::kBinary
                                 ? i * h_.stride + field.offset
                                 : h_.points * field.offset + i * field.size * field.count;
      first_values[f] = detail::decode_scalar(block_.data() + at, field.type, false);
    }
  }

  [[noreturn]] void fail(const std::string& problem) const {
    if (h_.data == Data::kAscii) r_.fail_at_line(problem);
    r_.fail(problem);
  }

 private:
  [[noreturn]] void too_many(std::uint64_t budget) const {
    r_.fail("header: POINTS " + std::to_string(h_.points) + " exceeds what " +
            std::to_string(budget) + " bytes of data can hold");
  }

  void decompress() {
    const std::string_view sizes = r_.take(8, "compressed data sizes");
    const auto compressed = detail::load_raw<std::uint32_t>(sizes.data(), false);
    const auto uncompressed = detail::load_raw<std::uint32_t>(sizes.data() + 4, false);
    if (h_.points > 0 && (h_.stride > UINT32_MAX || h_.points > UINT32_MAX / h_.stride ||
                          uncompressed != h_.points * h_.stride)) {
      r_.fail("header: POINTS " + std::to_string(h_.points) + " of " + std::to_string(h_.stride) +
              " bytes do not match the " + std::to_string(uncompressed) +
              " uncompressed bytes declared");
    }
    if (uncompressed > kMaxUncompressedBytes) {
      r_.fail("compressed data: " + std::to_string(uncompressed) +
              " uncompressed bytes declared, more than the limit of " +
              std::to_string(kMaxUncompressedBytes));
    }
    if (compressed > r_.remaining() ||
        uncompressed > std::uint64_t{compressed} * detail::kLzfMaxRatio) {
      r_.fail("compressed data: " + std::to_string(compressed) + " bytes declared (expanding to " +
              std::to_string(uncompressed) + "), " + std::to_string(r_.remaining()) +
              " bytes follow");
    }
    const std::string_view packed = r_.take(compressed, "compressed data");
    if (h_.points == 0) return;
    storage_.resize(uncompressed);
    if (!detail::lzf_decompress(packed, storage_.data(), storage_.size())) {
      r_.fail("compressed data: corrupt LZF stream");
    }
    block_ = storage_;
  }

  double ascii_value(std::uint64_t i) {
    const auto token = r_.next_token();
    if (!token) {
      fail("truncated: point " + std::to_string(i) + " of " + std::to_string(h_.points) +
           " ends early");
    }
    double value = 0.0;
    if (!detail::parse_double(*token, value)) fail("expected a number, found " + printable(*token));
    return value;
  }

  BoundedReader& r_;
  const PcdHeader& h_;
  std::string storage_;
  std::string_view block_;
};

}  // namespace

PointCloud read_pcd(const std::filesystem::path& path, CloudReadReport* report_out) {
  const std::string bytes = detail::load_file(path);
  BoundedReader r(path, bytes);
  const PcdHeader h = parse_pcd_header(r);
  const int x = find(h, "x"), y = find(h, "y"), z = find(h, "z");
  for (const char* axis : {"x", "y", "z"}) {
    if (find(h, axis) < 0) r.fail(std::string("header: no '") + axis + "' field");
  }
  int nx = find(h, "normal_x"), ny = find(h, "normal_y"), nz = find(h, "normal_z");
  if (nx < 0 || ny < 0 || nz < 0) nx = ny = nz = -1;
  int hi = find(h, detail::kStampHi), lo = find(h, detail::kStampLo);
  if (hi < 0 || lo < 0) hi = lo = -1;
  CloudReadReport report;
  report.points_in_file = h.points;
  const int used[] = {x, y, z, nx, ny, nz, hi, lo};
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    if (std::find(std::begin(used), std::end(used), static_cast<int>(i)) == std::end(used) &&
        h.fields[i].name != "_") {
      report.ignored_properties.push_back(h.fields[i].name);
    }
  }

  Values values(r, h);  // checks h.points against the data before anything is reserved
  PointCloud cloud;
  cloud.frame_id = h.frame_id;
  cloud.sensor = h.sensor;
  cloud.points.reserve(h.points);
  if (nx >= 0) cloud.normals.reserve(h.points);
  if (hi >= 0) cloud.stamps.reserve(h.points);
  const bool organised = h.height > 1;
  if (organised) {
    if (h.width > INT32_MAX || h.height > INT32_MAX || h.points > INT32_MAX) {
      r.fail("header: organised cloud of " + std::to_string(h.points) + " points is too large");
    }
    cloud.grid.rows = static_cast<int>(h.height);
    cloud.grid.cols = static_cast<int>(h.width);
    cloud.grid.index.assign(h.points, -1);
  }
  std::vector<double> v;
  for (std::uint64_t i = 0; i < h.points; ++i) {
    values.next_point(i, v);
    const Eigen::Vector3d p(v[x], v[y], v[z]);
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    if (nx >= 0) n = Eigen::Vector3d(v[nx], v[ny], v[nz]);
    if (!p.allFinite() || !n.allFinite()) {
      ++report.non_finite_dropped;
      continue;
    }
    if (organised) cloud.grid.index[i] = static_cast<std::int32_t>(cloud.points.size());
    cloud.points.push_back(p);
    if (nx >= 0) cloud.normals.push_back(n);
    if (hi >= 0) {
      const auto stamp = detail::join_stamp(v[hi], v[lo]);
      if (!stamp) values.fail("point " + std::to_string(i) + ": stamp words out of range");
      cloud.stamps.push_back(*stamp);
    }
  }
  if (report_out) *report_out = std::move(report);
  return cloud;
}

}  // namespace rangefit::io
