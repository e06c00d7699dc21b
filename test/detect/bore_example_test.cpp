// The example scan shipped in data/examples/ for the README demo: it is made by the synthetic
// generator below and must stay detectable with the CAD prior documented in
// data/examples/README.md. Regenerate it with
//   RANGEFIT_WRITE_EXAMPLES=1 build/test/detect/detect_test --gtest_filter='BoreExample.*'
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "detect/bore/bore_detector.hpp"
#include "io/cloud_io.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit {
namespace bore_example_test {

const std::filesystem::path kExample =
    std::filesystem::path(RANGEFIT_SOURCE_DIR) / "data/examples/bore_plate_r5.ply";

// A chamfered 5 mm bore slanted 30 deg in a plate; the part sits at (120, -40, 300) mm,
// turned 20 deg about x, seen from 25 deg off the bore axis.
sim::SyntheticBoreScan example_scan() {
  sim::SyntheticBoreOptions o;
  o.radius = 5.0;
  o.slant_deg = 30.0;
  o.edge = sim::BoreEdge::kChamfer;
  o.extent = 20.0;
  o.spacing = 0.2;
  o.seed = 2026;
  o.T_world_part = Eigen::Translation3d(120.0, -40.0, 300.0) *
                   Eigen::AngleAxisd(20.0 * std::numbers::pi / 180.0, Eigen::Vector3d::UnitX());
  return sim::make_synthetic_bore(o);
}

// The CAD prior of data/examples/README.md (about 0.4 mm and 2 deg off the truth).
BorePrior example_prior() {
  BorePrior prior;
  prior.entrance = {120.3, -40.2, 300.1};
  prior.axis = {0.5, -0.32, 0.81};
  prior.radius = 5.0;
  prior.plane_normal = Eigen::Vector3d(0.0, -0.342, 0.94);
  return prior;
}

TEST(BoreExample, ShippedScanIsFoundWithItsDocumentedPrior) {
  const sim::SyntheticBoreScan scan = example_scan();
  if (std::getenv("RANGEFIT_WRITE_EXAMPLES") != nullptr) {
    std::filesystem::create_directories(kExample.parent_path());
    io::write_cloud(kExample, scan.cloud);
  }
  const PointCloud cloud = io::read_cloud(kExample);
  ASSERT_EQ(cloud.size(), scan.cloud.size()) << "regenerate the example (see the header)";
  BoreOptions options;
  options.view_dir = scan.truth.view_dir;
  const BoreResult r = detect_bore(cloud, example_prior(), options);
  ASSERT_TRUE(r.found) << to_string(r.reason);
  EXPECT_LT((r.entrance - scan.truth.entrance).norm(), 0.3);
  EXPECT_GT(r.axis.dot(scan.truth.axis), std::cos(0.5 * std::numbers::pi / 180.0));
  EXPECT_NEAR(r.radius, 5.0, 0.1);
  std::printf("truth entrance %.4f %.4f %.4f axis %.5f %.5f %.5f view %.5f %.5f %.5f\n",
              scan.truth.entrance.x(), scan.truth.entrance.y(), scan.truth.entrance.z(),
              scan.truth.axis.x(), scan.truth.axis.y(), scan.truth.axis.z(),
              scan.truth.view_dir.x(), scan.truth.view_dir.y(), scan.truth.view_dir.z());
}

}  // namespace bore_example_test
}  // namespace rangefit
