// rangefit's PCD and PLY files as PCL users load them: pcl::io::loadPCDFile / loadPLYFile into
// pcl::PointXYZ and pcl::PointNormal must find x y z (and the normals) with rangefit's values,
// and an organised scan must keep its width x height with NaN in the empty cells. Built only
// where PCL is installed (libpcl-dev); the independent reader (check_cloud_files.py) covers the
// same files in every build.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "io/pcd.hpp"
#include "io/ply.hpp"
#include "test/io/cloud_fixtures.hpp"

namespace rangefit::io {
namespace pcl_load_test {
namespace fs = std::filesystem;

class PclLoad : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rangefit_pcl_load_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A plain cloud with normals and stamps (the extras PCL must skip).
  static PointCloud plain() {
    PointCloud c;
    c.points = {{1, 2, 3}, {-4.25, 5e-3, 600.5}, {0.1, -0.2, 1000.0 / 3.0}};
    c.normals = {Eigen::Vector3d::UnitX(), Eigen::Vector3d(0, 0.6, 0.8), -Eigen::Vector3d::UnitZ()};
    c.stamps = {std::chrono::nanoseconds(5), std::chrono::nanoseconds(1LL << 40),
                std::chrono::nanoseconds(-7)};
    return c;
  }

  fs::path dir_;
};

template <typename P>
void expect_points(const pcl::PointCloud<P>& loaded, const PointCloud& cloud) {
  ASSERT_EQ(loaded.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_FLOAT_EQ(loaded[i].x, static_cast<float>(cloud.points[i].x())) << "point " << i;
    EXPECT_FLOAT_EQ(loaded[i].y, static_cast<float>(cloud.points[i].y())) << "point " << i;
    EXPECT_FLOAT_EQ(loaded[i].z, static_cast<float>(cloud.points[i].z())) << "point " << i;
  }
}

void expect_normals(const pcl::PointCloud<pcl::PointNormal>& loaded, const PointCloud& cloud) {
  ASSERT_EQ(loaded.size(), cloud.normals.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_FLOAT_EQ(loaded[i].normal_x, static_cast<float>(cloud.normals[i].x())) << i;
    EXPECT_FLOAT_EQ(loaded[i].normal_y, static_cast<float>(cloud.normals[i].y())) << i;
    EXPECT_FLOAT_EQ(loaded[i].normal_z, static_cast<float>(cloud.normals[i].z())) << i;
  }
}

// `file` loads with `load` (pcl::io::loadPCDFile or loadPLYFile) into PointXYZ and PointNormal,
// with the cloud's points and normals.
template <class Load>
void expect_loads(const std::string& file, const PointCloud& cloud, Load load) {
  pcl::PointCloud<pcl::PointXYZ> xyz;
  ASSERT_EQ(load(file, xyz), 0) << file;
  expect_points(xyz, cloud);
  pcl::PointCloud<pcl::PointNormal> with_normals;
  ASSERT_EQ(load(file, with_normals), 0) << file;
  expect_points(with_normals, cloud);
  expect_normals(with_normals, cloud);
}

TEST_F(PclLoad, PcdBinaryAndAsciiLoadAsPointXYZAndPointNormal) {
  const PointCloud cloud = plain();
  for (PcdEncoding encoding : {PcdEncoding::kBinary, PcdEncoding::kAscii}) {
    const std::string file = path(encoding == PcdEncoding::kBinary ? "b.pcd" : "a.pcd");
    write_pcd(file, cloud, encoding);
    expect_loads(file, cloud, [](const std::string& f, auto& out) {
      return pcl::io::loadPCDFile(f, out);
    });
  }
}

TEST_F(PclLoad, OrganisedPcdKeepsWidthHeightAndNaNCells) {
  const PointCloud cloud = test::organised_cloud();
  write_pcd(path("organised.pcd"), cloud);
  pcl::PointCloud<pcl::PointXYZ> loaded;
  ASSERT_EQ(pcl::io::loadPCDFile(path("organised.pcd"), loaded), 0);
  EXPECT_EQ(loaded.width, static_cast<std::uint32_t>(cloud.grid.cols));
  EXPECT_EQ(loaded.height, static_cast<std::uint32_t>(cloud.grid.rows));
  EXPECT_TRUE(loaded.isOrganized());
  EXPECT_FALSE(loaded.is_dense);
  for (int r = 0; r < cloud.grid.rows; ++r) {
    for (int c = 0; c < cloud.grid.cols; ++c) {
      const pcl::PointXYZ& p = loaded.at(c, r);
      const std::int32_t i = cloud.grid.at(r, c);
      if (i < 0) {
        EXPECT_TRUE(std::isnan(p.x) && std::isnan(p.y) && std::isnan(p.z)) << r << "," << c;
        continue;
      }
      EXPECT_FLOAT_EQ(p.x, static_cast<float>(cloud.points[i].x())) << r << "," << c;
      EXPECT_FLOAT_EQ(p.y, static_cast<float>(cloud.points[i].y())) << r << "," << c;
      EXPECT_FLOAT_EQ(p.z, static_cast<float>(cloud.points[i].z())) << r << "," << c;
    }
  }
}

TEST_F(PclLoad, PlyLoadsAsPointXYZAndPointNormal) {
  const PointCloud cloud = plain();
  for (PlyEncoding encoding : {PlyEncoding::kBinaryLittleEndian, PlyEncoding::kBinaryBigEndian,
                               PlyEncoding::kAscii}) {
    const std::string file = path("cloud" + std::to_string(static_cast<int>(encoding)) + ".ply");
    write_ply(file, cloud, encoding);
    expect_loads(file, cloud, [](const std::string& f, auto& out) {
      return pcl::io::loadPLYFile(f, out);
    });
  }
}

}  // namespace pcl_load_test
}  // namespace rangefit::io
