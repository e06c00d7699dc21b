#include "io/cloud_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test/io/cloud_fixtures.hpp"
#include "test/io/temp_dir.hpp"

namespace rangefit::io {
namespace cloud_io_test {

using test::TempDir;
using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(CloudIo, DispatchesOnExtensionIgnoringCase) {
  TempDir dir;
  const PointCloud cloud = test::organised_cloud();
  for (const char* name : {"a.ply", "b.PLY", "c.pcd", "d.Pcd"}) {
    const auto file = dir.path(name);
    write_cloud(file, cloud, Precision::kFloat64);
    CloudReadReport report;
    const PointCloud back = read_cloud(file, &report);
    EXPECT_EQ(back.points, cloud.points) << name;
    EXPECT_EQ(back.grid.index, cloud.grid.index) << name;
  }
  EXPECT_THAT(TempDir::read(dir.path("b.PLY")), StartsWith("ply\n"));
  EXPECT_THAT(TempDir::read(dir.path("c.pcd")), StartsWith("# .PCD v0.7"));
}

TEST(CloudIo, EmptyCloudRoundTripsThroughBothFormats) {
  TempDir dir;
  for (const char* name : {"e.ply", "e.pcd"}) {
    write_cloud(dir.path(name), PointCloud{});
    EXPECT_TRUE(read_cloud(dir.path(name)).empty()) << name;
  }
}

TEST(CloudIo, UnknownExtensionIsAClearError) {
  TempDir dir;
  const auto file = dir.write("scan.xyz", "1 2 3\n");
  EXPECT_THAT([&] { read_cloud(file); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("scan.xyz: unknown point-cloud extension "
                                                          "'.xyz' (expected .ply or .pcd)")));
  EXPECT_THROW(write_cloud(dir.path("noext"), PointCloud{}), IoError);
}

TEST(CloudIo, ContentMustMatchTheExtension) {
  TempDir dir;
  write_cloud(dir.path("real.pcd"), test::organised_cloud());
  const auto renamed = dir.write("fake.ply", TempDir::read(dir.path("real.pcd")));
  EXPECT_THAT([&] { read_cloud(renamed); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("fake.ply: not a PLY file")));
}

// A scan remembers how it was taken, so detection on a saved stripe sweep knows the sensor's
// shadows as it did live.
TEST(CloudIo, SensorViewRoundTripsThroughBothFormats) {
  TempDir dir;
  PointCloud cloud = test::organised_cloud();
  cloud.sensor.kind = SensorView::Kind::kLinearSweep;
  cloud.sensor.origin = {1.5, -300.25, 612.0};
  cloud.sensor.plane_normal = Eigen::Vector3d(0.0, 0.6, 0.8);
  cloud.sensor.camera_offset = {0.0, 400.0, 1e-3};
  cloud.sensor.direction = Eigen::Vector3d::UnitY();
  cloud.sensor.sweep_min = -1.0 / 3.0;
  cloud.sensor.sweep_max = 420.0;
  // With one camera, and with a second across the laser plane.
  for (const Eigen::Vector3d& second :
       {Eigen::Vector3d::Zero().eval(), Eigen::Vector3d(0.0, -400.0, 2e-3)}) {
    cloud.sensor.second_camera_offset = second;
    for (const char* name : {"s.ply", "s.pcd"}) {
      write_cloud(dir.path(name), cloud);
      const SensorView back = read_cloud(dir.path(name)).sensor;
      EXPECT_EQ(back.kind, cloud.sensor.kind) << name;
      EXPECT_EQ(back.origin, cloud.sensor.origin) << name;
      EXPECT_EQ(back.plane_normal, cloud.sensor.plane_normal) << name;
      EXPECT_EQ(back.camera_offset, cloud.sensor.camera_offset) << name;
      EXPECT_EQ(back.second_camera_offset, second) << name;
      EXPECT_EQ(back.direction, cloud.sensor.direction) << name;
      EXPECT_EQ(back.sweep_min, cloud.sensor.sweep_min) << name;
      EXPECT_EQ(back.sweep_max, cloud.sensor.sweep_max) << name;
    }
  }
  // Without one the sensor stays unknown; a broken one is an error naming the line.
  write_cloud(dir.path("u.ply"), test::organised_cloud());
  EXPECT_EQ(read_cloud(dir.path("u.ply")).sensor.kind, SensorView::Kind::kUnknown);
  std::string text = TempDir::read(dir.path("s.ply"));
  text.replace(text.find("linear_sweep"), 12, "warp_drive");
  const auto bad = dir.write("bad.ply", text);
  EXPECT_THAT([&] { read_cloud(bad); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("'rangefit sensor' is not a kind")));
}

}  // namespace cloud_io_test
}  // namespace rangefit::io
