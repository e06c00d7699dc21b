// Two cells on one DDS domain: each rangefitd in its own ROS namespace ([ros] namespace) or DDS
// partition ([dds] partition). Each client gets only its own cell's answers and topics, under
// the names a ROS 2 node of that namespace uses (rt/cell1/rangefit/..., rq/cell1/rangefit/...,
// frames "cell1/...").
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <thread>

#include "daemon/dds/client.hpp"
#include "daemon/dds/ros_service.hpp"
#include "daemon/rangefitd/service.hpp"
#include "test/daemon/fakes.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/daemon/xcdr_reader.hpp"

namespace rangefit::daemon {
namespace ros_namespace_test {
namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;
using test::Cdr;
using test::take_bytes;

// One in-process rangefitd whose scans have `points` points, so its answers are its own.
struct Cell {
  Cell(const std::string& name, const std::string& ns, const std::string& partition, int points)
      : dir(test::fresh_test_dir(fs::path("rangefit_ros_namespace_test") / name)) {
    DaemonConfig config = test::replay_css_config(dir, dir / "scan.ply");
    config.dds.ros_namespace = ns;
    config.dds.partition = partition;
    auto backend = std::make_unique<test::FakeBackend>();
    backend->points = points;
    service = std::make_unique<Service>(config, clock, std::move(backend),
                                        std::make_unique<test::CentroidDetector>());
    loop = std::make_unique<test::ServiceLoop>(*service);
  }
  ~Cell() {
    loop.reset();
    service.reset();
    fs::remove_all(dir);
  }
  fs::path dir;
  hal::MonotonicClock clock;
  std::unique_ptr<Service> service;
  std::unique_ptr<test::ServiceLoop> loop;
};

ScanRequest bore_request(const std::string& id) {
  ScanRequest req;
  req.id = id;
  req.bore.radius_mm = 5;
  return req;
}

// Sends the same request id through both clients; each must get its own cell's answer and,
// within a grace period, no other.
void expect_each_client_gets_only_its_cell(DdsClient& one, DdsClient& two) {
  ASSERT_TRUE(one.wait_for_daemon(seconds(20)));
  ASSERT_TRUE(two.wait_for_daemon(seconds(20)));
  ASSERT_TRUE(one.send(bore_request("same-id"), false));
  ASSERT_TRUE(two.send(bore_request("same-id"), false));
  const auto a = one.wait_result("same-id", seconds(20));
  const auto b = two.wait_result("same-id", seconds(20));
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->num_points, 100u) << "cell one scans 100 points";
  EXPECT_EQ(b->num_points, 40u) << "cell two scans 40 points";
  int more = 0;
  const auto deadline = std::chrono::steady_clock::now() + milliseconds(500);
  while (std::chrono::steady_clock::now() < deadline) {
    DdsClient::Callbacks cb;
    cb.detection = [&](const DetectionResult&) { ++more; };
    one.poll(milliseconds(50), cb);
    two.poll(milliseconds(50), cb);
  }
  EXPECT_EQ(more, 0) << "an answer of the other cell arrived";
}

TEST(RosNamespace, TwoCellsInTwoNamespacesAnswerOnlyTheirOwnClients) {
  const Cell cell1("ns1", "cell1", "", 100), cell2("ns2", "cell2", "", 40);
  DdsClient one(test::dds_test_domain(), "cell1"), two(test::dds_test_domain(), "cell2");
  expect_each_client_gets_only_its_cell(one, two);
}

TEST(RosNamespace, TwoCellsInTwoPartitionsAnswerOnlyTheirOwnClients) {
  const Cell cell1("p1", "", "cell_one", 100), cell2("p2", "", "cell_two", 40);
  DdsClient one(test::dds_test_domain(), "", "cell_one"),
      two(test::dds_test_domain(), "", "cell_two");
  expect_each_client_gets_only_its_cell(one, two);
}

TEST(RosNamespace, TopicsServiceAndFramesAreTheNamespacedRosNames) {
  const Cell cell1("names1", "cell1", "", 100), cell2("names2", "cell2", "", 40);
  dds::Participant p(test::dds_test_domain());
  dds::Reader<geometry_msgs_msg_dds__PoseArray_> poses(
      p, "rt/cell1/rangefit/poses", &geometry_msgs_msg_dds__PoseArray__desc, topics::latched_qos());
  // Depth 2: rt/tf_static is keyless, so the two cells' latched samples share one history.
  dds::Reader<tf2_msgs_msg_dds__TFMessage_> tf_static(
      p, topics::kTfStatic, &tf2_msgs_msg_dds__TFMessage__desc, dds::QosSpec{true, true, 2});
  dds::Writer<rangefit_msgs_srv_dds__Detect_Request_> calls(
      p, "rq/cell1/rangefit/detectRequest", &rangefit_msgs_srv_dds__Detect_Request__desc,
      topics::service_qos());
  dds::Reader<rangefit_msgs_srv_dds__Detect_Response_> replies(
      p, "rr/cell1/rangefit/detectReply", &rangefit_msgs_srv_dds__Detect_Response__desc,
      dds::QosSpec{true, false, 10});
  for (int i = 0; i < 2000 && (calls.matched() == 0 || replies.matched() == 0); ++i) {
    std::this_thread::sleep_for(milliseconds(10));
  }
  ASSERT_EQ(calls.matched(), 1) << "only cell1 serves /cell1/rangefit/detect";
  rangefit_msgs_srv_dds__Detect_Request_ call{};
  call.rmw_client_guid = 7;
  call.rmw_sequence_number = 1;
  call.request_id = const_cast<char*>("");
  call.kind = const_cast<char*>("bore");
  call.model = const_cast<char*>("");
  call.sensor = const_cast<char*>("");
  call.bore_axis = {0, 0, 1};
  call.bore_radius = 0.005;
  ASSERT_TRUE(calls.write(call));
  const auto reply = take_bytes(replies.get(), seconds(20));
  ASSERT_TRUE(reply);
  Cdr r{*reply};
  EXPECT_EQ(r.get<std::uint64_t>(), 7u);
  r.get<std::int64_t>();
  r.get<std::int32_t>();
  r.get<std::uint32_t>();
  EXPECT_EQ(r.str(), "cell1/world") << "the world frame with the namespace's prefix";

  const auto pose_bytes = take_bytes(poses.get(), seconds(20));
  ASSERT_TRUE(pose_bytes);
  Cdr q{*pose_bytes};
  q.get<std::int32_t>();
  q.get<std::uint32_t>();
  EXPECT_EQ(q.str(), "cell1/world");
  EXPECT_EQ(q.get<std::uint32_t>(), 1u);

  // rt/tf_static is global: both cells' mounts arrive, each below its own prefixed world.
  std::set<std::string> mounts;
  for (int i = 0; i < 2; ++i) {
    const auto bytes = take_bytes(tf_static.get(), seconds(20));
    ASSERT_TRUE(bytes);
    Cdr t{*bytes};
    ASSERT_EQ(t.get<std::uint32_t>(), 1u);
    t.get<std::int32_t>();
    t.get<std::uint32_t>();
    const std::string parent = t.str();
    mounts.insert(parent + " -> " + t.str());
  }
  EXPECT_EQ(mounts,
            (std::set<std::string>{"cell1/world -> cell1/css", "cell2/world -> cell2/css"}));
}

}  // namespace ros_namespace_test
}  // namespace rangefit::daemon
