#include "daemon/service/spool.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test/daemon/fakes.hpp"

namespace rangefit::daemon {
namespace spool_test {
namespace fs = std::filesystem;

class SpoolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "rangefit_spool_test" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SpoolTest, EntryRoundTripsRequestCloudAndResult) {
  Spool spool({dir_, 1ull << 30, 24.0});
  std::string why;
  ASSERT_TRUE(spool.open(&why)) << why;
  ScanRequest req;
  req.id = "bore/1 ../x";
  req.bore.radius_mm = 5;
  DetectionResult res;
  res.request_id = req.id;
  res.found = true;
  res.bore_radius_mm = 5.01;
  PartPose part;
  part.name = "bore";
  part.T_world_part.translation() = Eigen::Vector3d(1, 2, 3);
  res.parts.push_back(part);
  ASSERT_TRUE(spool.write(req, test::grid_cloud(50), res, &why)) << why;
  // The id cannot escape the spool directory.
  EXPECT_EQ(fs::path(res.spool_entry).parent_path(), dir_);
  const auto e = read_spool_entry(res.spool_entry, &why);
  ASSERT_TRUE(e) << why;
  EXPECT_EQ(e->request.id, req.id);
  EXPECT_DOUBLE_EQ(e->request.bore.radius_mm, 5.0);
  EXPECT_EQ(e->cloud.size(), 50u);
  EXPECT_TRUE(e->cloud.points[49].isApprox(test::grid_cloud(50).points[49]));
  EXPECT_DOUBLE_EQ(e->result.bore_radius_mm, 5.01);
  EXPECT_TRUE(e->result.parts.at(0).T_world_part.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST_F(SpoolTest, EmptyCloudIsSpooledToo) {
  Spool spool({dir_, 1ull << 30, 24.0});
  std::string why;
  ASSERT_TRUE(spool.open(&why));
  ScanRequest req;
  req.id = "empty";
  DetectionResult res = DetectionResult::error(req, "scan failed");
  ASSERT_TRUE(spool.write(req, PointCloud{}, res, &why)) << why;
  const auto e = read_spool_entry(res.spool_entry, &why);
  ASSERT_TRUE(e) << why;
  EXPECT_TRUE(e->cloud.empty());
  EXPECT_EQ(e->result.reason, "scan failed");
}

TEST_F(SpoolTest, SizeBoundRemovesTheOldestEntriesFirst) {
  Spool spool({dir_, 1 << 20, 24.0});
  std::string why;
  ASSERT_TRUE(spool.open(&why));
  std::vector<std::string> entries;
  for (int i = 0; i < 6; ++i) {  // ~240 kB each: PLY doubles, 10,000 points
    ScanRequest req;
    req.id = "r";
    req.id += std::to_string(i);
    DetectionResult res;
    ASSERT_TRUE(spool.write(req, test::grid_cloud(10000), res, &why)) << why;
    entries.push_back(res.spool_entry);
  }
  EXPECT_LE(spool.total_bytes(), 1u << 20);
  EXPECT_FALSE(fs::exists(entries.front()));
  EXPECT_TRUE(fs::exists(entries.back()));
}

TEST_F(SpoolTest, AgeBoundRemovesExpiredEntries) {
  Spool spool({dir_, 1ull << 30, 1.0});
  std::string why;
  ASSERT_TRUE(spool.open(&why));
  ScanRequest req;
  req.id = "old";
  DetectionResult res;
  ASSERT_TRUE(spool.write(req, test::grid_cloud(10), res, &why));
  EXPECT_EQ(spool.prune(fs::file_time_type::clock::now() + std::chrono::minutes(30)), 0u);
  EXPECT_EQ(spool.prune(fs::file_time_type::clock::now() + std::chrono::hours(2)), 1u);
  EXPECT_EQ(spool.entry_count(), 0u);
}

TEST_F(SpoolTest, MissingOrBrokenEntryIsAnErrorNotACrash) {
  std::string why;
  EXPECT_FALSE(read_spool_entry(dir_ / "nope", &why));
  EXPECT_NE(why.find("missing"), std::string::npos);
  fs::create_directories(dir_ / "bad");
  for (const char* f : {"request.json", "result.json", "cloud.ply"}) {
    std::ofstream(dir_ / "bad" / f) << "{not json";
  }
  EXPECT_FALSE(read_spool_entry(dir_ / "bad", &why));
}

}  // namespace spool_test
}  // namespace rangefit::daemon
