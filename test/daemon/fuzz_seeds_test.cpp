// The DDS messages fuzzer's request seeds (test/fuzz/corpus/dds_messages, made by
// test/fuzz/request_seeds.py) decode with today's DetectRequest and service request types: a
// field added to the IDL without the seeds rewritten leaves every seed dropped by Cyclone's
// receive path, and the fuzzer would never reach the request checks again.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "daemon/dds/messages.hpp"
#include "daemon/dds/service_request.hpp"
#include "test/fuzz/wire_sample.hpp"

namespace rangefit::daemon {
namespace fuzz_seeds_test {
namespace fs = std::filesystem;

std::vector<std::uint8_t> bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const fs::path kCorpus = fs::path(RANGEFIT_SOURCE_DIR) / "test/fuzz/corpus/dds_messages";

// A topic request seed as the daemon decodes it (its first byte picks the message).
ScanRequest decode_request_seed(const std::string& name, std::string* error) {
  const std::vector<std::uint8_t> b = bytes_of(kCorpus / name);
  if (b.size() < 2) {
    *error = "no seed " + name;
    return {};
  }
  const test::WireSample<rangefit_msgs_msg_dds__DetectRequest_> msg(
      rangefit_msgs_msg_dds__DetectRequest__desc, std::span(b.data() + 1, b.size() - 1));
  if (msg.get() == nullptr) {
    *error = "seed " + name + " does not decode";
    return {};
  }
  return from_msg(*msg.get(), error);
}

TEST(FuzzSeeds, EveryRequestSeedDecodesWithTheCurrentTypes) {
  int requests = 0, services = 0;
  for (const auto& entry : fs::directory_iterator(kCorpus)) {
    const std::string name = entry.path().filename().string();
    const std::vector<std::uint8_t> b = bytes_of(entry.path());
    ASSERT_FALSE(b.empty()) << name;
    const std::span<const std::uint8_t> sample(b.data() + 1, b.size() - 1);
    // The harness's first byte picks the message: 1 the topic request, 4 the service request.
    if (b[0] % 5 == 1 && name.find("request") != std::string::npos) {
      const test::WireSample<rangefit_msgs_msg_dds__DetectRequest_> msg(
          rangefit_msgs_msg_dds__DetectRequest__desc, sample);
      EXPECT_NE(msg.get(), nullptr) << name << " does not decode as a DetectRequest";
      ++requests;
    } else if (b[0] % 5 == 4) {
      const test::WireSample<rangefit_msgs_srv_dds__Detect_Request_> msg(
          rangefit_msgs_srv_dds__Detect_Request__desc, sample);
      EXPECT_NE(msg.get(), nullptr) << name << " does not decode as a service request";
      ++services;
    }
  }
  EXPECT_GE(requests, 8);
  EXPECT_GE(services, 9);
}

// The learn seed carries the sensors of a fused learn, and they come out of the decoding.
TEST(FuzzSeeds, TheLearnSeedNamesTwoSensors) {
  std::string error;
  const ScanRequest req = decode_request_seed("request_learn", &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(req.kind, DetectKind::kLearn);
  EXPECT_EQ(req.sensors, (std::vector<std::string>{"stripe", "head"}));
  // A seed written before the css fields existed has them "not given".
  EXPECT_EQ(req.target.radius_mm, 0.0);
  EXPECT_FALSE(req.target.T_base_joint);
  EXPECT_TRUE(req.target.scans.empty());
  // Nor the pantilt tilt.
  EXPECT_FALSE(req.target.tilt_rad);
}

// The css calibration seed carries the sphere, the robot pose and two earlier scans, in mm.
TEST(FuzzSeeds, TheCssCalibrateSeedCarriesTheSphereThePoseAndTheScans) {
  std::string error;
  const ScanRequest req = decode_request_seed("request_calibrate_css", &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(req.kind, DetectKind::kCalibrate);
  EXPECT_EQ(req.target.kind, "css");
  EXPECT_NEAR(req.target.radius_mm, 12.5, 1e-9);
  ASSERT_TRUE(req.target.T_base_joint);
  EXPECT_LT((req.target.T_base_joint->translation() - Eigen::Vector3d(450, -100, 600)).norm(),
            1e-9);
  EXPECT_EQ(req.target.scans, (std::vector<std::string>{"css-pose-1", "css-pose-2"}));
}

// The pantilt calibration seed carries the cube's pose in mm, the tilt given and one earlier
// sweep.
TEST(FuzzSeeds, ThePantiltCalibrateSeedCarriesTheTiltAndTheScans) {
  std::string error;
  const ScanRequest req = decode_request_seed("request_calibrate_pantilt", &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(req.kind, DetectKind::kCalibrate);
  EXPECT_EQ(req.target.kind, "pantilt");
  EXPECT_LT((req.target.T_table_target.translation() - Eigen::Vector3d(900, -40, 250)).norm(),
            1e-9);
  ASSERT_TRUE(req.target.tilt_rad);
  EXPECT_EQ(*req.target.tilt_rad, 0.1);
  EXPECT_EQ(req.target.scans, (std::vector<std::string>{"sweep-1"}));
  EXPECT_FALSE(req.target.T_base_joint);
}

}  // namespace fuzz_seeds_test
}  // namespace rangefit::daemon
