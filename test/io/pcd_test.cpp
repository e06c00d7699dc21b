#include "io/pcd.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <liblzf/lzf.h>
#include <sys/stat.h>

#include <limits>
#include <string>

#include "io/lzf.hpp"
#include "test/io/cloud_fixtures.hpp"
#include "test/io/temp_dir.hpp"

namespace rangefit::io {
namespace pcd_test {

using test::append_le;
using test::TempDir;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string pcd_error(const std::filesystem::path& file) {
  try {
    read_pcd(file);
  } catch (const IoError& e) {
    return e.what();
  }
  return "no IoError";
}

// A valid LZF stream made of literal runs only (no back references), as liblzf emits for data
// without repeats; enough to build binary_compressed files.
std::string lzf_literals(const std::string& data) {
  std::string out;
  for (std::size_t i = 0; i < data.size(); i += 32) {
    const std::size_t n = std::min<std::size_t>(32, data.size() - i);
    out += static_cast<char>(n - 1);
    out += data.substr(i, n);
  }
  return out;
}

std::string header(const std::string& fields, const std::string& size, const std::string& type,
                   std::int64_t width, std::int64_t height, const std::string& data) {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " +
         size + "\nTYPE " + type + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " +
         std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(width * height) + "\nDATA " + data + "\n";
}

class PcdRoundTrip : public ::testing::TestWithParam<PcdEncoding> {};

TEST_P(PcdRoundTrip, KeepsPointsNormalsStampsGridAndFrame) {
  TempDir dir;
  const PointCloud cloud = test::organised_cloud();
  const auto file = dir.path("scan.pcd");
  write_pcd(file, cloud, GetParam(), Precision::kFloat64);
  CloudReadReport report;
  const PointCloud back = read_pcd(file, &report);
  EXPECT_EQ(back.points, cloud.points);
  EXPECT_EQ(back.normals, cloud.normals);
  EXPECT_EQ(back.stamps, cloud.stamps);
  EXPECT_EQ(back.grid.rows, 3);
  EXPECT_EQ(back.grid.cols, 4);
  EXPECT_EQ(back.grid.index, cloud.grid.index);
  EXPECT_EQ(back.frame_id, "css_scan");
  EXPECT_EQ(report.points_in_file, 12u);  // every cell, the two empty ones as NaN
  EXPECT_EQ(report.non_finite_dropped, 2u);
  EXPECT_TRUE(report.ignored_properties.empty());
}

TEST_P(PcdRoundTrip, EmptyCloudStaysEmpty) {
  TempDir dir;
  const auto file = dir.path("empty.pcd");
  write_pcd(file, PointCloud{}, GetParam());
  const PointCloud back = read_pcd(file);
  EXPECT_TRUE(back.empty());
  EXPECT_FALSE(back.organised());
}

TEST_P(PcdRoundTrip, UnorganisedCloudStaysUnorganised) {
  TempDir dir;
  PointCloud cloud;
  cloud.points = {{1, 2, 3}, {-4.25, 5e-7, 6e8}, {0, 0, -0.0}};
  const auto file = dir.path("plain.pcd");
  write_pcd(file, cloud, GetParam(), Precision::kFloat64);
  const PointCloud back = read_pcd(file);
  EXPECT_EQ(back.points, cloud.points);
  EXPECT_FALSE(back.organised());
  EXPECT_FALSE(back.has_normals());
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdRoundTrip,
                         ::testing::Values(PcdEncoding::kAscii, PcdEncoding::kBinary));

TEST(PcdRead, PclAsciiWithPackedRgbAndNanPoints) {
  TempDir dir;
  const auto file = dir.write("pcl.pcd",
                              "# .PCD v.7 - Point Cloud Data file format\n"
                              "VERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F F\n"
                              "COUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                              "POINTS 3\nDATA ascii\n"
                              "0.93773 0.33763 0 4.2108e+06\n"
                              "nan nan nan 4.2108e+06\n"
                              "-0.5 1e-3 12 4.2108e+06\n");
  CloudReadReport report;
  const PointCloud cloud = read_pcd(file, &report);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3d(-0.5, 1e-3, 12));
  EXPECT_EQ(report.points_in_file, 3u);
  EXPECT_EQ(report.non_finite_dropped, 1u);
  EXPECT_THAT(report.ignored_properties, ElementsAre("rgb"));
}

TEST(PcdRead, PclBinaryPointNormalWithPaddingAndCurvature) {
  TempDir dir;
  std::string bytes =
      "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
      "FIELDS x y z _ normal_x normal_y normal_z _ curvature\n"
      "SIZE 4 4 4 1 4 4 4 1 4\nTYPE F F F U F F F U F\nCOUNT 1 1 1 4 1 1 1 4 1\n"
      "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA binary\n";
  for (int i = 0; i < 2; ++i) {
    for (float v : {1.0f + static_cast<float>(i), 2.0f, 3.0f}) append_le(bytes, v);
    bytes.append(4, '\0');
    for (float v : {0.0f, 0.0f, 1.0f}) append_le(bytes, v);
    bytes.append(4, '\0');
    append_le(bytes, 0.25f);
  }
  CloudReadReport report;
  const PointCloud cloud = read_pcd(dir.write("pn.pcd", bytes), &report);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3d(2, 2, 3));
  EXPECT_EQ(cloud.normals[1], Eigen::Vector3d(0, 0, 1));
  EXPECT_THAT(report.ignored_properties, ElementsAre("curvature"));
}

TEST(PcdRead, BinaryCompressedOrganisedCloudFillsGridWithEmptyNanCells) {
  TempDir dir;
  // 2 x 2 organised, fields stored one after another: all x, then all y, then all z (int16).
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::string raw;
  for (float v : {0.0f, 1.0f, nan, 3.0f}) append_le(raw, v);
  for (float v : {10.0f, 11.0f, 12.0f, 13.0f}) append_le(raw, v);
  for (int v : {-1, -2, -3, -4}) append_le(raw, static_cast<std::int16_t>(v));
  const std::string packed = lzf_literals(raw);
  std::string bytes = header("x y z", "4 4 2", "F F I", 2, 2, "binary_compressed");
  append_le(bytes, static_cast<std::uint32_t>(packed.size()));
  append_le(bytes, static_cast<std::uint32_t>(raw.size()));
  bytes += packed;
  const PointCloud cloud = read_pcd(dir.write("org.pcd", bytes));
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.grid.rows, 2);
  EXPECT_EQ(cloud.grid.cols, 2);
  EXPECT_THAT(cloud.grid.index, ElementsAre(0, 1, -1, 2));
  EXPECT_EQ(cloud.points[2], Eigen::Vector3d(3, 13, -4));
}

TEST(PcdRead, LzfBackReferencesMayOverlapTheirOutput) {
  const std::string stream = std::string(
      "\x01"
      "ab"
      "\x40\x01",
      5);  // "ab", then copy 4 from 2 back
  std::string out(6, '\0');
  ASSERT_TRUE(detail::lzf_decompress(stream, out.data(), out.size()));
  EXPECT_EQ(out, "ababab");
  std::string small(5, '\0');
  EXPECT_FALSE(detail::lzf_decompress(stream, small.data(), small.size()));
  const std::string before_start("\x40\x05", 2);  // refers to bytes before the output
  EXPECT_FALSE(detail::lzf_decompress(before_start, out.data(), out.size()));
}

TEST(PcdRead, BinaryCompressedFromLiblzfsCompressorReadsBack) {
  // A scan plane at z = 5 with a regular grid repeats most bytes, so the compressor emits back
  // references as PCL's writer does.
  TempDir dir;
  constexpr int kW = 40, kH = 30;
  std::string raw;
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i < kW * kH; ++i)
      append_le(raw, axis == 0   ? static_cast<float>(i % kW)
                     : axis == 1 ? static_cast<float>(i / kW)
                                 : 5.0f);
  std::string packed(raw.size() + 64, '\0');
  const unsigned n = lzf_compress(raw.data(), static_cast<unsigned>(raw.size()), packed.data(),
                                  static_cast<unsigned>(packed.size()));
  ASSERT_GT(n, 0u);
  packed.resize(n);
  ASSERT_LT(packed.size(), raw.size() / 4);  // back references did the work
  std::string bytes = header("x y z", "4 4 4", "F F F", kW, kH, "binary_compressed");
  append_le(bytes, static_cast<std::uint32_t>(packed.size()));
  append_le(bytes, static_cast<std::uint32_t>(raw.size()));
  bytes += packed;
  const PointCloud cloud = read_pcd(dir.write("plane.pcd", bytes));
  ASSERT_EQ(cloud.size(), static_cast<std::size_t>(kW * kH));
  EXPECT_EQ(cloud.points[kW * 7 + 3], Eigen::Vector3d(3, 7, 5));
  // The same stream one byte short must be an IoError, never a partial cloud.
  std::string cut = header("x y z", "4 4 4", "F F F", kW, kH, "binary_compressed");
  append_le(cut, static_cast<std::uint32_t>(packed.size() - 1));
  append_le(cut, static_cast<std::uint32_t>(raw.size()));
  cut += packed.substr(0, packed.size() - 1);
  EXPECT_NE(pcd_error(dir.write("cut.pcd", cut)), "no IoError");
}

TEST(PcdRead, HugePointCountIsRejectedBeforeAllocating) {
  TempDir dir;
  std::string bytes = header("x y z", "4 4 4", "F F F", 2000000000, 2, "binary");
  bytes += std::string(1200, '\0');
  EXPECT_THAT(pcd_error(dir.write("scan.pcd", bytes)),
              HasSubstr("scan.pcd: header: POINTS 4000000000 exceeds what 1200 bytes of data "
                        "can hold"));
}

TEST(PcdRead, EachHeaderProblemHasItsMessage) {
  TempDir dir;
  EXPECT_THAT(pcd_error(dir.write("a.pcd", header("x y z", "4 4 4", "F F Q", 1, 1, "ascii"))),
              HasSubstr("a.pcd: header: field 'z' has unsupported TYPE 'Q' with SIZE '4'"));
  EXPECT_THAT(pcd_error(dir.write("b.pcd", header("x y z", "4 4", "F F F", 1, 1, "ascii"))),
              HasSubstr("b.pcd: header: 3 FIELDS but 2 SIZE and 3 TYPE entries"));
  EXPECT_THAT(pcd_error(dir.write("c.pcd", header("x y", "4 4", "F F", 1, 1, "ascii"))),
              HasSubstr("c.pcd: header: no 'z' field"));
  EXPECT_THAT(pcd_error(dir.write("d.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n")),
              HasSubstr("d.pcd: header: truncated, no DATA line"));
  EXPECT_THAT(pcd_error(dir.write("e.pcd",
                                  "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\n"
                                  "HEIGHT 2\nPOINTS 5\nDATA ascii\n")),
              HasSubstr("e.pcd: header: POINTS 5 is not WIDTH 2 x HEIGHT 2"));
  EXPECT_THAT(pcd_error(dir.write("f.pcd", "FIELDS x y z\nWIDTH -3\n")),
              HasSubstr("f.pcd: line 2: header: WIDTH '-3' is not a non-negative integer"));
  EXPECT_THAT(pcd_error(dir.write("g.pcd", header("x y z", "4 4 4", "F F F", 1, 1, "lzma"))),
              HasSubstr("header: unknown DATA 'lzma'"));
  EXPECT_THAT(pcd_error(dir.write("h.pcd", "FIELDS x y z\nCOLOUR red\n")),
              HasSubstr("h.pcd: line 2: header: unknown keyword 'COLOUR'"));
  EXPECT_THAT(pcd_error(dir.path("missing.pcd")), HasSubstr("missing.pcd: cannot open"));
}

TEST(PcdRead, DataProblemsAreNamed) {
  TempDir dir;
  const std::string ascii = header("x y z", "4 4 4", "F F F", 2, 1, "ascii");
  EXPECT_THAT(pcd_error(dir.write("a.pcd", ascii + "1 2 3\n4 5 six\n")),
              HasSubstr("a.pcd: line 12: expected a number, found 'six'"));
  EXPECT_THAT(pcd_error(dir.write("b.pcd", ascii + "1.0 2.0 3.0\n4.0\n")),
              HasSubstr("b.pcd: line 12: truncated: point 1 of 2 ends early"));
  std::string compressed = header("x y z", "4 4 4", "F F F", 1, 1, "binary_compressed");
  append_le(compressed, std::uint32_t{3});
  append_le(compressed, std::uint32_t{12});
  compressed += std::string("\x1f\x00\x00", 3);  // literal run of 32 bytes with 2 present
  EXPECT_THAT(pcd_error(dir.write("c.pcd", compressed)),
              HasSubstr("c.pcd: compressed data: corrupt"));
  std::string wrong_size = header("x y z", "4 4 4", "F F F", 1, 1, "binary_compressed");
  append_le(wrong_size, std::uint32_t{3});
  append_le(wrong_size, std::uint32_t{4000000000u});
  wrong_size += "abc";
  EXPECT_THAT(pcd_error(dir.write("d.pcd", wrong_size)),
              HasSubstr("do not match the 4000000000 uncompressed bytes declared"));
}

TEST(PcdRead, DecompressedSizeHasAnAbsoluteCap) {
  // 12 bytes a point: just over 256 MiB of points declared by a ~3 MB file (88x, LZF's worst
  // case, so the relative bound alone lets it through); refused before allocating.
  TempDir dir;
  const std::uint32_t points = (256u << 20) / 12u + 1u;
  std::string big = header("x y z", "4 4 4", "F F F", points, 1, "binary_compressed");
  const std::uint32_t compressed = (points * 12u) / 88u + 1u;
  append_le(big, compressed);
  append_le(big, std::uint32_t{points * 12u});
  big += std::string(compressed, '\0');
  EXPECT_THAT(pcd_error(dir.write("big.pcd", big)),
              HasSubstr("big.pcd: compressed data: 268435464 uncompressed bytes declared, more "
                        "than the limit of 268435456"));
}

TEST(PcdRead, SpecialFilesAreRefusedWithoutBlocking) {
  TempDir dir;
  EXPECT_THAT(pcd_error("/dev/zero"), HasSubstr("/dev/zero: is not a regular file"));
  const auto fifo = dir.path("cloud.pcd");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(pcd_error(fifo), HasSubstr("cloud.pcd: is not a regular file"));
  EXPECT_THAT(pcd_error(dir.path("")), HasSubstr("is a directory"));
}

TEST(PcdWrite, RejectsPointOutsideTheGrid) {
  TempDir dir;
  PointCloud cloud = test::organised_cloud();
  cloud.grid.index[0] = -1;  // point 0 is now in no cell
  EXPECT_THAT([&] { write_pcd(dir.path("a.pcd"), cloud); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("point 0 is in no grid cell")));
}

}  // namespace pcd_test
}  // namespace rangefit::io
