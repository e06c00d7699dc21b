// A sweep that covers only part of the table cuts the objects of the fig. 5.18 scene at its
// edges: with the cone inside the sweep (140..240 mm of the stripe axis) the cone is reported
// where it is, and with the cone outside it (220..400, 0..150) nothing the sweep's edges cut is
// taken for it: the detector gets the sweep's range as its visibility model.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "daemon/rangefitd/service.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/daemon/stripe_cell_config.hpp"

namespace rangefit::daemon {
namespace partial_sweep_test {
namespace fs = std::filesystem;

struct Sweep {
  double from_mm, to_mm;
  bool cone_inside;
};

class PartialSweep : public ::testing::TestWithParam<Sweep> {};

TEST_P(PartialSweep, TheConeIsFoundWhereItIsOrNotAtAll) {
  const fs::path dir = test::fresh_test_dir("rangefit_partial_sweep_test");
  const ConfigResult config = load_config(
      test::write_stripe_cell_config(dir, "table_top_fig5_18.toml", "cone.toml", false));
  ASSERT_TRUE(config.config) << config.error;
  hal::MonotonicClock clock;
  Service service(*config.config, clock);
  auto loop = std::make_unique<test::ServiceLoop>(service);
  ScanRequest req;
  req.id = "cone-partial";
  req.kind = DetectKind::kObject;
  req.model = "cone";
  req.seed = 1;
  req.sweep_start = GetParam().from_mm * kMetresPerMm;  // admit() takes the wire's unit
  req.sweep_end = GetParam().to_mm * kMetresPerMm;
  ASSERT_TRUE(service.board().reserve(req.id));
  ASSERT_FALSE(service.admit(req));
  const auto result = service.board().wait_for(req.id, std::chrono::seconds(120));
  loop.reset();
  ASSERT_TRUE(result);
  if (!GetParam().cone_inside) {
    EXPECT_FALSE(result->found);
    EXPECT_EQ(result->reason, "not confirmed");
    fs::remove_all(dir);
    return;
  }
  ASSERT_TRUE(result->found) << result->reason;
  const Eigen::Isometry3d& T = result->parts.at(0).T_world_part;
  EXPECT_LT((T.translation() - Eigen::Vector3d(213.074, 110.438, 40.0)).norm(), 3.0)
      << T.translation().transpose() << " axis " << T.linear().col(2).transpose();
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Sweeps, PartialSweep,
                         ::testing::Values(Sweep{140.0, 240.0, true}, Sweep{220.0, 400.0, false},
                                           Sweep{0.0, 150.0, false}),
                         [](const auto& p) {
                           return std::to_string(static_cast<int>(p.param.from_mm)) + "_" +
                                  std::to_string(static_cast<int>(p.param.to_mm));
                         });

}  // namespace partial_sweep_test
}  // namespace rangefit::daemon
