// The request fields added beside the CLI's options survive the wire (metres and all), an older
// client's request (the new fields zero) means what it meant before, and validation names the
// field that is out of range.
#include <gtest/gtest.h>

#include "daemon/dds/messages.hpp"
#include "daemon/service/request_validation.hpp"

namespace rangefit::daemon {
namespace request_fields_test {

TEST(RequestFields, PlaneNormalCountsAndSeedRoundTripTheWire) {
  ScanRequest req;
  req.id = "request-1";
  req.kind = DetectKind::kObject;
  req.model = "cylinder";
  req.bore.plane_normal = Eigen::Vector3d(0, -0.342, 0.94);
  req.instances = 3;
  req.hypotheses = 40;
  req.trials = 7;
  req.seed = 123456789012345ull;
  const RequestOut out(req, false);
  std::string error;
  const ScanRequest back = from_msg(out.msg(), &error);
  EXPECT_EQ(error, "");
  ASSERT_TRUE(back.bore.plane_normal);
  EXPECT_EQ(*back.bore.plane_normal, *req.bore.plane_normal);
  EXPECT_EQ(back.instances, 3);
  EXPECT_EQ(back.hypotheses, 40);
  EXPECT_EQ(back.trials, 7);
  EXPECT_EQ(back.seed, req.seed);
}

TEST(RequestFields, AnOlderClientsZerosMeanTheEarlierDefaults) {
  ScanRequest req;
  req.id = "old";
  req.kind = DetectKind::kBore;
  req.bore.radius_mm = 5;
  req.instances = 0;
  const RequestOut out(req, false);
  std::string error;
  ScanRequest back = from_msg(out.msg(), &error);
  EXPECT_FALSE(back.bore.plane_normal);  // zero vector: the axis, as before
  EXPECT_EQ(back.seed, 0u);              // the configured seed
  DaemonConfig config;
  DeviceConfig css;
  css.name = css.kind = "css";
  config.devices.push_back(css);
  config.service.bore_sensor = "css";
  EXPECT_EQ(validate_request(back, config), "");
  EXPECT_EQ(back.instances, 1);
  back.trials = 20000;
  EXPECT_EQ(validate_request(back, config),
            "trials must be in 0 .. 10000 (0: the detector's default)");
}

}  // namespace request_fields_test
}  // namespace rangefit::daemon
