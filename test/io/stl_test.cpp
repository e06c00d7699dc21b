#include "io/stl.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "test/io/temp_dir.hpp"

namespace rangefit::io {
namespace stl_test {

using test::TempDir;
using ::testing::HasSubstr;

// A unit tetrahedron: 4 shared vertices, 4 faces.
TriangleMesh tetrahedron() {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

void append_float(std::string& out, float v) {
  char b[4];
  std::memcpy(b, &v, 4);
  out.append(b, 4);
}

std::string binary_stl(std::string header, const std::vector<std::array<float, 9>>& facets) {
  header.resize(80, ' ');
  std::string out = header;
  const auto n = static_cast<std::uint32_t>(facets.size());
  out.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : facets) {
    for (int k = 0; k < 3; ++k) append_float(out, 0.0f);
    for (float v : f) append_float(out, v);
    out.append(2, '\0');
  }
  return out;
}

TEST(Stl, BinaryRoundTripKeepsSharedVertices) {
  TempDir dir;
  const auto file = dir.path("tetra.stl");
  write_stl(file, tetrahedron());
  EXPECT_EQ(TempDir::read(file).size(), 84u + 4u * 50u);
  const TriangleMesh mesh = read_stl(file);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 4u);
  const TriangleMesh expected = tetrahedron();
  for (std::size_t t = 0; t < 4; ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(mesh.vertices[mesh.triangles[t][c]], expected.vertices[expected.triangles[t][c]]);
    }
  }
}

TEST(Stl, EmptyMeshRoundTrips) {
  TempDir dir;
  const auto file = dir.path("empty.stl");
  write_stl(file, TriangleMesh{});
  const TriangleMesh mesh = read_stl(file);
  EXPECT_TRUE(mesh.vertices.empty());
  EXPECT_TRUE(mesh.triangles.empty());
}

TEST(Stl, AsciiFileLoadsAndMergesVertices) {
  TempDir dir;
  const auto file = dir.write("two.stl",
                              "solid part\r\n"
                              "  facet normal 0 0 1\r\n"
                              "    outer loop\r\n"
                              "      vertex 0 0 0\r\n"
                              "      vertex 1 0 0\r\n"
                              "      vertex 0 1 0\r\n"
                              "    endloop\r\n"
                              "  endfacet\r\n"
                              "  facet normal 0 0 1\n"
                              "    outer loop\n"
                              "      vertex 1 0 0\n"
                              "      vertex 1.0e0 1 -0\n"
                              "      vertex 0 1 0\n"
                              "    endloop\n"
                              "  endfacet\n"
                              "endsolid part\n");
  const TriangleMesh mesh = read_stl(file);
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.vertices.size(), 4u);  // two corners shared, -0 merged with 0
  EXPECT_EQ(mesh.triangles[1][0], mesh.triangles[0][1]);
  EXPECT_EQ(mesh.triangles[1][2], mesh.triangles[0][2]);
}

TEST(Stl, BinaryFileWhoseHeaderStartsWithSolidIsReadAsBinary) {
  TempDir dir;
  const auto file = dir.write(
      "solidworks.stl", binary_stl("solid exported by a CAD tool", {{0, 0, 0, 1, 0, 0, 0, 1, 0}}));
  const TriangleMesh mesh = read_stl(file);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.vertices[mesh.triangles[0][1]], Eigen::Vector3d(1, 0, 0));
}

TEST(Stl, HugeTriangleCountIsRejectedBeforeAllocating) {
  TempDir dir;
  std::string bytes = binary_stl("hostile", {{0, 0, 0, 1, 0, 0, 0, 1, 0}});
  const std::uint32_t huge = 4000000000u;
  std::memcpy(bytes.data() + 80, &huge, 4);
  const auto file = dir.write("huge.stl", bytes);
  try {
    read_stl(file);
    FAIL() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("huge.stl"));
    EXPECT_THAT(e.what(), HasSubstr("triangle count 4000000000"));
  }
}

TEST(Stl, MalformedAsciiNamesTheLine) {
  TempDir dir;
  const auto file =
      dir.write("bad.stl", "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 zero\n");
  try {
    read_stl(file);
    FAIL() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.stl: line 4"));
    EXPECT_THAT(e.what(), HasSubstr("'zero'"));
  }
}

TEST(Stl, FacetWithFourVerticesIsRejected) {
  TempDir dir;
  const auto file = dir.write(
      "quad.stl",
      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n");
  EXPECT_THROW(read_stl(file), IoError);
}

TEST(Stl, NonFiniteBinaryVertexIsRejected) {
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto file = dir.write("nan.stl", binary_stl("x", {{0, 0, 0, nan, 0, 0, 0, 1, 0}}));
  EXPECT_THROW(read_stl(file), IoError);
}

TEST(Stl, ShortFileAndMissingFileAreErrors) {
  TempDir dir;
  EXPECT_THROW(read_stl(dir.write("short.stl", "abc")), IoError);
  EXPECT_THROW(read_stl(dir.write("empty.stl", "")), IoError);
  EXPECT_THROW(read_stl(dir.path("missing.stl")), IoError);
}

TEST(Stl, WriteRejectsTriangleWithMissingVertex) {
  TempDir dir;
  TriangleMesh mesh = tetrahedron();
  mesh.triangles.push_back({0, 1, 7});
  EXPECT_THROW(write_stl(dir.path("bad.stl"), mesh), IoError);
}

}  // namespace stl_test
}  // namespace rangefit::io
