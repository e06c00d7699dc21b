#include "io/stl.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>

#include "io/bounded_reader.hpp"
#include "io/scalar.hpp"

namespace rangefit::io {
namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kTriangleBytes = 50;  // normal, 3 vertices (12 float32), attribute uint16

// Merges bit-identical vertices while triangles are added.
class MeshBuilder {
 public:
  explicit MeshBuilder(std::size_t expected_triangles) {
    mesh_.triangles.reserve(expected_triangles);
    index_.reserve(expected_triangles);
  }

  std::uint32_t vertex(Eigen::Vector3d v) {
    v += Eigen::Vector3d::Zero();  // -0.0 + 0.0 == +0.0, so both zeros share a key
    Key key{};
    for (int i = 0; i < 3; ++i) std::memcpy(&key[i], &v[i], sizeof(double));
    const auto [it, inserted] =
        index_.try_emplace(key, static_cast<std::uint32_t>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(v);
    return it->second;
  }

  void triangle(const std::array<Eigen::Vector3d, 3>& corners) {
    mesh_.triangles.push_back({vertex(corners[0]), vertex(corners[1]), vertex(corners[2])});
  }

  TriangleMesh take() { return std::move(mesh_); }

 private:
  using Key = std::array<std::uint64_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0xcbf29ce484222325ull;
      for (std::uint64_t part : k) h = (h ^ part) * 0x100000001b3ull + (h >> 29);
      return static_cast<std::size_t>(h);
    }
  };
  TriangleMesh mesh_;
  std::unordered_map<Key, std::uint32_t, KeyHash> index_;
};

TriangleMesh read_binary(detail::BoundedReader& reader, std::uint32_t count) {
  MeshBuilder builder(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const std::string_view record = reader.take(kTriangleBytes, "triangle " + std::to_string(t));
    std::array<Eigen::Vector3d, 3> corners;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) {
        const char* at = record.data() + 12 + 12 * c + 4 * k;
        corners[c][k] = detail::load_raw<float>(at, false);
      }
      if (!corners[c].allFinite()) {
        reader.fail("triangle " + std::to_string(t) + " has a non-finite vertex");
      }
    }
    builder.triangle(corners);
  }
  return builder.take();
}

double ascii_number(detail::BoundedReader& reader) {
  const auto token = reader.next_token();
  double value = 0.0;
  if (!token) reader.fail_at_line("truncated: expected a number, found the end of the file");
  if (!detail::parse_double(*token, value) || !std::isfinite(value)) {
    reader.fail_at_line("expected a finite number, found " + detail::printable(*token));
  }
  return value;
}

TriangleMesh read_ascii(detail::BoundedReader& reader) {
  // Each facet takes well over 60 bytes of text; a reservation of size/64 is safe.
  MeshBuilder builder(reader.remaining() / 64);
  std::array<Eigen::Vector3d, 3> corners;
  int corner_count = -1;  // -1 outside an "outer loop"
  bool in_solid = false;
  while (const auto token = reader.next_token()) {
    const std::string_view word = *token;
    if (word == "solid") {
      if (in_solid) reader.fail_at_line("'solid' inside a solid");
      in_solid = true;
      reader.next_line();  // the solid's name runs to the end of the line (may be empty)
    } else if (word == "endsolid") {
      if (!in_solid) reader.fail_at_line("'endsolid' without 'solid'");
      in_solid = false;
      reader.next_line();
    } else if (word == "facet" || word == "normal") {
      if (!in_solid) reader.fail_at_line(detail::printable(word) + " outside a solid");
      if (word == "normal") {
        for (int k = 0; k < 3; ++k) ascii_number(reader);  // recomputed from the vertex order
      }
    } else if (word == "outer" || word == "loop") {
      if (word == "loop") {
        if (corner_count != -1) reader.fail_at_line("nested 'outer loop'");
        corner_count = 0;
      }
    } else if (word == "vertex") {
      if (corner_count < 0) reader.fail_at_line("'vertex' outside 'outer loop'");
      if (corner_count == 3) reader.fail_at_line("facet with more than 3 vertices");
      Eigen::Vector3d& v = corners[static_cast<std::size_t>(corner_count++)];
      for (int k = 0; k < 3; ++k) v[k] = ascii_number(reader);
    } else if (word == "endloop") {
      if (corner_count != 3) {
        reader.fail_at_line("facet with " + std::to_string(std::max(corner_count, 0)) +
                            " vertices, STL needs 3");
      }
      builder.triangle(corners);
      corner_count = -1;
    } else if (word == "endfacet") {
      if (corner_count != -1) reader.fail_at_line("'endfacet' before 'endloop'");
    } else {
      reader.fail_at_line("unexpected word " + detail::printable(word));
    }
  }
  if (in_solid || corner_count != -1) reader.fail("truncated: ASCII STL ends inside a solid");
  return builder.take();
}

}  // namespace

TriangleMesh read_stl(const std::filesystem::path& path) {
  const std::string bytes = detail::load_file(path);
  detail::BoundedReader reader(path, bytes);
  std::uint32_t count = 0;
  bool size_matches_binary = false;
  if (bytes.size() >= kHeaderBytes + 4) {
    count = detail::load_raw<std::uint32_t>(bytes.data() + kHeaderBytes, false);
    size_matches_binary = bytes.size() == kHeaderBytes + 4 + kTriangleBytes * std::size_t{count};
  }
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  const bool looks_ascii = first != std::string::npos && bytes.compare(first, 5, "solid") == 0;
  if (looks_ascii && !size_matches_binary) return read_ascii(reader);
  if (bytes.size() < kHeaderBytes + 4) {
    reader.fail("truncated: " + std::to_string(bytes.size()) +
                " bytes is neither an ASCII STL nor a binary STL header (84 bytes)");
  }
  const std::size_t needed = kTriangleBytes * std::size_t{count};
  if (needed > bytes.size() - kHeaderBytes - 4) {
    reader.fail("header: triangle count " + std::to_string(count) + " needs " +
                std::to_string(needed) + " bytes, only " +
                std::to_string(bytes.size() - kHeaderBytes - 4) + " follow");
  }
  reader.take(kHeaderBytes + 4, "header");
  return read_binary(reader, count);  // trailing bytes after the triangles are tolerated
}

void write_stl(const std::filesystem::path& path, const TriangleMesh& mesh) {
  if (mesh.triangles.size() > UINT32_MAX) throw IoError(path, "too many triangles for STL");
  std::string out;
  out.reserve(kHeaderBytes + 4 + kTriangleBytes * mesh.triangles.size());
  // The header must not start with "solid", or naive readers take the file for ASCII.
  std::string header = "binary STL written by rangefit, units mm";
  header.resize(kHeaderBytes, ' ');
  out += header;
  detail::append_raw(out, static_cast<std::uint32_t>(mesh.triangles.size()), false);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<Eigen::Vector3d, 3> corners;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t index = mesh.triangles[t][static_cast<std::size_t>(c)];
      if (index >= mesh.vertices.size()) {
        throw IoError(path, "triangle " + std::to_string(t) + " refers to vertex " +
                                std::to_string(index) + " of " +
                                std::to_string(mesh.vertices.size()));
      }
      corners[static_cast<std::size_t>(c)] = mesh.vertices[index];
    }
    Eigen::Vector3d normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    normal = normal.norm() > 0.0 ? Eigen::Vector3d(normal.normalized()) : Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) detail::append_raw(out, static_cast<float>(normal[k]), false);
    for (const Eigen::Vector3d& v : corners) {
      for (int k = 0; k < 3; ++k) detail::append_raw(out, static_cast<float>(v[k]), false);
    }
    detail::append_raw(out, std::uint16_t{0}, false);
  }
  detail::save_file(path, out);
}

}  // namespace rangefit::io
