// What other tools read: float32 positions and normals by default (PCL's point types), float64 on
// request, and standard input/output for command-line pipes.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <limits>
#include <string>

#include "io/cloud_io.hpp"
#include "io/pcd.hpp"
#include "io/ply.hpp"
#include "test/io/cloud_fixtures.hpp"
#include "test/io/temp_dir.hpp"

namespace rangefit::io {
namespace cloud_precision_test {

using test::TempDir;
using ::testing::HasSubstr;
using ::testing::Not;

std::vector<Eigen::Vector3d> as_float(const std::vector<Eigen::Vector3d>& values) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& v : values) out.push_back(v.cast<float>().cast<double>());
  return out;
}

// Binary files hold the floats themselves; ASCII ones their shortest text, which a reader parsing
// doubles reads as the nearest double, so there the floats must match.
void expect_float_copy(const PointCloud& back, const PointCloud& cloud, bool ascii = false) {
  EXPECT_EQ(ascii ? as_float(back.points) : back.points, as_float(cloud.points));
  EXPECT_NE(as_float(back.points), cloud.points);  // the fixture has values float cannot hold
  EXPECT_EQ(ascii ? as_float(back.normals) : back.normals, as_float(cloud.normals));
  EXPECT_EQ(back.stamps, cloud.stamps);  // integer words, exact whatever the precision
  EXPECT_EQ(back.grid.index, cloud.grid.index);
  EXPECT_EQ(back.frame_id, cloud.frame_id);
}

TEST(CloudPrecision, PlyIsFloatByDefaultInEveryEncoding) {
  TempDir dir;
  const PointCloud cloud = test::organised_cloud();
  for (const PlyEncoding encoding :
       {PlyEncoding::kAscii, PlyEncoding::kBinaryLittleEndian, PlyEncoding::kBinaryBigEndian}) {
    const auto file = dir.path("scan.ply");
    write_ply(file, cloud, encoding);
    const std::string text = TempDir::read(file);
    EXPECT_THAT(text, HasSubstr("property float x\nproperty float y\nproperty float z\n"
                                "property float nx\nproperty float ny\nproperty float nz\n"));
    EXPECT_THAT(text.substr(0, text.find("end_header")), Not(HasSubstr("double")));
    expect_float_copy(read_ply(file), cloud, encoding == PlyEncoding::kAscii);
  }
}

TEST(CloudPrecision, PcdIsFloatByDefaultLikePclPointNormal) {
  TempDir dir;
  const PointCloud cloud = test::organised_cloud();
  for (const PcdEncoding encoding : {PcdEncoding::kAscii, PcdEncoding::kBinary}) {
    const auto file = dir.path("scan.pcd");
    write_pcd(file, cloud, encoding);
    const std::string text = TempDir::read(file);
    EXPECT_THAT(text, HasSubstr("FIELDS x y z normal_x normal_y normal_z rangefit_stamp_hi "
                                "rangefit_stamp_lo\nSIZE 4 4 4 4 4 4 4 4\nTYPE F F F F F F I U\n"));
    EXPECT_THAT(text, HasSubstr("\nWIDTH 4\nHEIGHT 3\n"));  // organised: cols x rows
    expect_float_copy(read_pcd(file), cloud, encoding == PcdEncoding::kAscii);
  }
  // 12 cells of 8 four-byte fields after the header: the binary layout PCL maps onto PointNormal.
  const auto file = dir.path("sizes.pcd");
  write_pcd(file, cloud);
  const std::string text = TempDir::read(file);
  EXPECT_EQ(text.size() - (text.find("DATA binary\n") + 12), 12u * 8 * 4);
}

TEST(CloudPrecision, DoubleOnRequestKeepsEveryBit) {
  TempDir dir;
  const PointCloud cloud = test::organised_cloud();
  write_cloud(dir.path("a.ply"), cloud, Precision::kFloat64);
  write_cloud(dir.path("a.pcd"), cloud, Precision::kFloat64);
  EXPECT_THAT(TempDir::read(dir.path("a.ply")), HasSubstr("property double x\n"));
  EXPECT_THAT(TempDir::read(dir.path("a.pcd")), HasSubstr("\nSIZE 8 8 8 8 8 8 4 4\n"));
  for (const char* name : {"a.ply", "a.pcd"}) {
    const PointCloud back = read_cloud(dir.path(name));
    EXPECT_EQ(back.points, cloud.points) << name;
    EXPECT_EQ(back.normals, cloud.normals) << name;
  }
}

TEST(CloudPrecision, ValueBeyondFloatIsAnErrorNotInfinity) {
  TempDir dir;
  PointCloud cloud;
  cloud.points = {{1, 2, 3}, {0, -1e39, 0}};
  for (const char* name : {"big.ply", "big.pcd"}) {
    EXPECT_THAT([&] { write_cloud(dir.path(name), cloud); },
                ::testing::ThrowsMessage<IoError>(
                    HasSubstr("cannot write point 1 as float32: beyond its range")))
        << name;
    write_cloud(dir.path(name), cloud, Precision::kFloat64);
    EXPECT_EQ(read_cloud(dir.path(name)).points, cloud.points) << name;
  }
  // Infinity itself converts exactly; the readers drop it like any non-finite point.
  cloud.points[1].y() = std::numeric_limits<double>::infinity();
  write_cloud(dir.path("inf.ply"), cloud);
  CloudReadReport report;
  EXPECT_EQ(read_cloud(dir.path("inf.ply"), &report).size(), 1u);
  EXPECT_EQ(report.non_finite_dropped, 1u);
}

// Points file descriptor `fd` (0 or 1) at `file` while alive, as a shell redirection would.
class Redirect {
 public:
  Redirect(int fd, const std::filesystem::path& file, int flags) : fd_(fd), saved_(dup(fd)) {
    std::fflush(nullptr);
    const int opened = open(file.c_str(), flags, 0644);
    dup2(opened, fd_);
    close(opened);
  }
  ~Redirect() {
    std::fflush(nullptr);
    dup2(saved_, fd_);
    close(saved_);
  }
  Redirect(const Redirect&) = delete;
  Redirect& operator=(const Redirect&) = delete;

 private:
  int fd_, saved_;
};

TEST(CloudStdio, DashReadsStandardInputOfEitherFormat) {
  TempDir dir;
  const PointCloud cloud = test::organised_cloud();
  for (const char* name : {"in.ply", "in.pcd"}) {
    write_cloud(dir.path(name), cloud);
    PointCloud back;
    {
      Redirect in(STDIN_FILENO, dir.path(name), O_RDONLY);
      back = read_cloud("-");
    }
    expect_float_copy(back, cloud);
  }
  const auto junk = dir.write("junk", "not a cloud\n");
  std::string error;
  {
    Redirect in(STDIN_FILENO, junk, O_RDONLY);
    try {
      read_cloud("-");
    } catch (const IoError& e) {
      error = e.what();
    }
  }
  EXPECT_THAT(error, ::testing::StartsWith("stdin: "));
  EXPECT_THAT(error, Not(HasSubstr("/proc/self/fd")));
}

TEST(CloudStdio, DashWritesStandardOutputAsPlyUnlessTold) {
  TempDir dir;
  const PointCloud cloud = test::organised_cloud();
  {
    Redirect out(STDOUT_FILENO, dir.path("out"), O_WRONLY | O_CREAT | O_TRUNC);
    write_cloud("-", cloud);
  }
  EXPECT_THAT(TempDir::read(dir.path("out")), ::testing::StartsWith("ply\n"));
  {
    Redirect out(STDOUT_FILENO, dir.path("out"), O_WRONLY | O_CREAT | O_TRUNC);
    write_cloud("-", cloud, Precision::kFloat64, CloudFormat::kPcd);
  }
  TempDir::write_to(dir.path("out.pcd"), TempDir::read(dir.path("out")));
  const PointCloud back = read_cloud(dir.path("out.pcd"));
  EXPECT_EQ(back.points, cloud.points);
  EXPECT_EQ(back.grid.index, cloud.grid.index);
}

}  // namespace cloud_precision_test
}  // namespace rangefit::io
