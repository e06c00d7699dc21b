#include "io/cloud_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test/io/cloud_fixtures.hpp"
#include "test/io/temp_dir.hpp"

namespace rangefit::io {
namespace {

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

}  // namespace
}  // namespace rangefit::io
