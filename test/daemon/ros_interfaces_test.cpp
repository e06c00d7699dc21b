// What a ROS 2 node on the cell's network receives from rangefitd: the ROS type names on the
// rt/ topics, XCDR1 bytes, SI metres and the configured frames; the sensors' mounts latched on
// /tf_static, every part of a detection on /tf and rt/rangefit/poses; the service
// /rangefit/detect answered with the caller's identity, as rmw_cyclonedds matches replies; and
// the node on ros_discovery_info, as the ROS 2 graph lists it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "daemon/dds/client.hpp"
#include "daemon/dds/ros_discovery.hpp"
#include "daemon/dds/ros_service.hpp"
#include "daemon/rangefitd/service.hpp"
#include "test/daemon/fakes.hpp"
#include "test/daemon/replay_service.hpp"
#include "test/daemon/xcdr_reader.hpp"

namespace rangefit::daemon {
namespace ros_interfaces_test {
namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

using test::Cdr;
using test::take_bytes;
using test::type_name;

class RosInterfacesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_dir(fs::path("rangefit_ros_interfaces_test") /
                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
    config_ = test::replay_css_config(dir_, dir_ / "scan.ply");
    config_.devices[0].xyz_mm = {100, -200, 300};
    config_.devices[0].rpy_rad = {0, 0, M_PI / 2};
    config_.frames.world = "cell_base";
    config_.frames.sensors["css"] = "css_mount";
    auto backend = std::make_unique<test::FakeBackend>();
    service_ = std::make_unique<Service>(config_, clock_, std::move(backend),
                                         std::make_unique<test::CentroidDetector>());
    loop_ = std::make_unique<test::ServiceLoop>(*service_);
  }
  void TearDown() override {
    loop_.reset();
    service_.reset();
    fs::remove_all(dir_);
  }
  template <class T>
  std::unique_ptr<dds::Reader<T>> reader(const char* topic, const dds_topic_descriptor_t* desc,
                                         const dds::QosSpec& qos) {
    return std::make_unique<dds::Reader<T>>(participant_, topic, desc, qos);
  }

  fs::path dir_;
  DaemonConfig config_;
  hal::MonotonicClock clock_;
  std::unique_ptr<Service> service_;
  std::unique_ptr<test::ServiceLoop> loop_;
  dds::Participant participant_{test::dds_test_domain()};
};

TEST_F(RosInterfacesTest, SensorMountIsLatchedOnTfStaticInMetresFromTheWorldFrame) {
  auto tf_static = reader<tf2_msgs_msg_dds__TFMessage_>(
      topics::kTfStatic, &tf2_msgs_msg_dds__TFMessage__desc, topics::tf_static_qos());
  EXPECT_EQ(type_name(tf_static->get()), "tf2_msgs::msg::dds_::TFMessage_");
  const auto bytes = take_bytes(tf_static->get(), seconds(20));
  ASSERT_TRUE(bytes);
  EXPECT_EQ((*bytes)[0], 0x00);  // CDR_LE: XCDR1, as rmw_cyclonedds reads it
  EXPECT_EQ((*bytes)[1], 0x01);
  Cdr cdr{*bytes};
  ASSERT_EQ(cdr.get<std::uint32_t>(), 1u);  // one transform: the css
  cdr.get<std::int32_t>();                  // stamp
  cdr.get<std::uint32_t>();
  EXPECT_EQ(cdr.str(), "cell_base");
  EXPECT_EQ(cdr.str(), "css_mount");
  EXPECT_NEAR(cdr.get<double>(), 0.1, 1e-12);  // metres
  EXPECT_NEAR(cdr.get<double>(), -0.2, 1e-12);
  EXPECT_NEAR(cdr.get<double>(), 0.3, 1e-12);
  const double qx = cdr.get<double>(), qy = cdr.get<double>(), qz = cdr.get<double>(),
               qw = cdr.get<double>();
  EXPECT_NEAR(qx, 0, 1e-12);  // yaw 90 degrees
  EXPECT_NEAR(qy, 0, 1e-12);
  EXPECT_NEAR(qz, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(qw, std::sqrt(0.5), 1e-12);
}

TEST_F(RosInterfacesTest, EveryPartIsAPoseInPoseArrayAndATfFrameInTheConfiguredWorldFrame) {
  auto poses = reader<geometry_msgs_msg_dds__PoseArray_>(
      topics::kPoses, &geometry_msgs_msg_dds__PoseArray__desc, topics::latched_qos());
  auto tf = reader<tf2_msgs_msg_dds__TFMessage_>(topics::kTf, &tf2_msgs_msg_dds__TFMessage__desc,
                                                 topics::tf_qos());
  EXPECT_EQ(type_name(poses->get()), "geometry_msgs::msg::dds_::PoseArray_");
  DdsClient client(config_.dds.domain_id);
  ASSERT_TRUE(client.wait_for_daemon(seconds(20)));
  for (int i = 0; i < 200 && (tf->matched() == 0 || poses->matched() == 0); ++i) {
    std::this_thread::sleep_for(milliseconds(10));
  }
  ScanRequest req;
  req.id = "frames";
  req.bore.radius_mm = 5;
  ASSERT_TRUE(client.send(req, false));
  const auto result = client.wait_result("frames", seconds(20));
  ASSERT_TRUE(result && result->found);
  const Eigen::Vector3d mm = result->parts.at(0).T_world_part.translation();

  const auto pose_bytes = take_bytes(poses->get(), seconds(10));
  ASSERT_TRUE(pose_bytes);
  Cdr p{*pose_bytes};
  p.get<std::int32_t>();
  p.get<std::uint32_t>();
  EXPECT_EQ(p.str(), "cell_base");
  ASSERT_EQ(p.get<std::uint32_t>(), 1u);
  EXPECT_NEAR(p.get<double>(), mm.x() * 1e-3, 1e-12);
  EXPECT_NEAR(p.get<double>(), mm.y() * 1e-3, 1e-12);
  EXPECT_NEAR(p.get<double>(), mm.z() * 1e-3, 1e-12);

  const auto tf_bytes = take_bytes(tf->get(), seconds(10));
  ASSERT_TRUE(tf_bytes);
  Cdr t{*tf_bytes};
  ASSERT_EQ(t.get<std::uint32_t>(), 1u);
  t.get<std::int32_t>();
  t.get<std::uint32_t>();
  EXPECT_EQ(t.str(), "cell_base");
  EXPECT_EQ(t.str(), "rangefit/bore/centroid/0");
  EXPECT_NEAR(t.get<double>(), mm.x() * 1e-3, 1e-12);
}

// The request is framed as rmw_cyclonedds_cpp frames one (serdata.hpp: cdds_request_header_t
// { uint64_t guid; int64_t seq; } before the message); the reply must carry the same two.
TEST_F(RosInterfacesTest, ServiceCallIsAnsweredOnTheReplyTopicWithTheCallersIdentity) {
  dds::Writer<rangefit_msgs_srv_dds__Detect_Request_> requests(
      participant_, topics::kServiceRequest, &rangefit_msgs_srv_dds__Detect_Request__desc,
      topics::service_qos());
  auto replies = reader<rangefit_msgs_srv_dds__Detect_Response_>(
      topics::kServiceReply, &rangefit_msgs_srv_dds__Detect_Response__desc,
      dds::QosSpec{true, false, 10});  // rclcpp's default service QoS
  EXPECT_EQ(type_name(replies->get()), "rangefit_msgs::srv::dds_::Detect_Response_");
  for (int i = 0; i < 2000 && (requests.matched() == 0 || replies->matched() == 0); ++i) {
    std::this_thread::sleep_for(milliseconds(10));
  }
  ASSERT_GT(requests.matched(), 0);
  rangefit_msgs_srv_dds__Detect_Request_ call{};
  call.rmw_client_guid = 0x0123456789abcdefull;
  call.rmw_sequence_number = 42;
  call.request_id = const_cast<char*>("");  // `ros2 service call` with the defaults
  call.kind = const_cast<char*>("bore");
  call.model = const_cast<char*>("");
  call.sensor = const_cast<char*>("");
  call.bore_axis = {0, 0, 1};
  call.bore_radius = 0.005;  // metres
  ASSERT_TRUE(requests.write(call));
  const auto bytes = take_bytes(replies->get(), seconds(20));
  ASSERT_TRUE(bytes);
  Cdr r{*bytes};
  EXPECT_EQ(r.get<std::uint64_t>(), 0x0123456789abcdefull);
  EXPECT_EQ(r.get<std::int64_t>(), 42);
  r.get<std::int32_t>();
  r.get<std::uint32_t>();
  EXPECT_EQ(r.str(), "cell_base");
  EXPECT_EQ(r.str(), "ros-0123456789abcdef-42");  // the id the daemon gave the call
  EXPECT_EQ(r.str(), "bore");
  EXPECT_EQ(r.get<std::uint8_t>(), 1) << "found";
}

// The node a ROS 2 graph lists (ros2 node list: /rangefitd): rmw_cyclonedds's
// ParticipantEntitiesInfo on ros_discovery_info, whose Gids are the DDS GUIDs that built-in
// discovery announces for the daemon's participant, its writers and its readers.
using Guid = std::array<unsigned char, 16>;

Guid guid_bytes(const dds_guid_t& g) {
  Guid out;
  std::memcpy(out.data(), g.v, out.size());
  return out;
}

struct Endpoint {
  Guid key, participant;
  std::string type_name;
};

// The endpoint on `topic` that built-in discovery (DCPSPublication or DCPSSubscription) reports.
std::optional<Endpoint> discovered(dds_entity_t participant, dds_entity_t builtin,
                                   const std::string& topic) {
  const dds_entity_t r = dds_create_reader(participant, builtin, nullptr, nullptr);
  const auto deadline = std::chrono::steady_clock::now() + seconds(20);
  std::optional<Endpoint> found;
  while (!found && std::chrono::steady_clock::now() < deadline) {
    void* samples[64] = {};
    dds_sample_info_t infos[64];
    const dds_return_t n = dds_read(r, samples, infos, 64, 64);
    for (dds_return_t i = 0; i < n; ++i) {
      const auto* e = static_cast<const dds_builtintopic_endpoint_t*>(samples[i]);
      if (infos[i].valid_data && e->topic_name != nullptr && topic == e->topic_name) {
        found = Endpoint{guid_bytes(e->key), guid_bytes(e->participant_key),
                         e->type_name != nullptr ? e->type_name : ""};
      }
    }
    if (n > 0) dds_return_loan(r, samples, n);
    if (!found) std::this_thread::sleep_for(milliseconds(20));
  }
  dds_delete(r);
  return found;
}

// A Gid of `size` bytes (16 from Iron on, 24 in Humble): the GUID, then zeros.
Guid gid(Cdr& cdr, std::size_t size = 16) {
  Guid g;
  for (unsigned char& c : g) c = cdr.get<std::uint8_t>();
  for (std::size_t i = g.size(); i < size; ++i) {
    EXPECT_EQ(cdr.get<std::uint8_t>(), 0) << "byte " << i << " of a Gid after the GUID";
  }
  return g;
}

std::vector<Guid> gid_seq(Cdr& cdr, std::size_t size = 16) {
  std::vector<Guid> out(cdr.get<std::uint32_t>());
  for (Guid& g : out) g = gid(cdr, size);
  return out;
}

TEST_F(RosInterfacesTest, TheDaemonIsARosNodeWhoseEndpointsAreItsDiscoveredGuids) {
  auto info = reader<rmw_dds_common_msg_dds__ParticipantEntitiesInfo_>(
      topics::kRosDiscovery, &rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc,
      topics::ros_discovery_qos());
  EXPECT_EQ(type_name(info->get()), "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_");
  const auto bytes = take_bytes(info->get(), seconds(20));
  ASSERT_TRUE(bytes);
  Cdr cdr{*bytes};
  const Guid participant = gid(cdr);
  ASSERT_EQ(cdr.get<std::uint32_t>(), 1u);  // one node
  EXPECT_EQ(cdr.str(), "/");
  EXPECT_EQ(cdr.str(), "rangefitd");
  const std::vector<Guid> readers = gid_seq(cdr);
  const std::vector<Guid> writers = gid_seq(cdr);
  EXPECT_TRUE(cdr.done());
  const auto has = [](const std::vector<Guid>& v, const Guid& g) {
    return std::find(v.begin(), v.end(), g) != v.end();
  };
  const auto result = discovered(participant_.get(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION,
                                 topics::kDetections);
  ASSERT_TRUE(result);
  EXPECT_EQ(result->participant, participant);
  EXPECT_TRUE(has(writers, result->key));
  const auto reply = discovered(participant_.get(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION,
                                topics::kServiceReply);
  ASSERT_TRUE(reply);
  EXPECT_TRUE(has(writers, reply->key));
  for (const char* topic : {topics::kRequest, topics::kServiceRequest}) {
    const auto request =
        discovered(participant_.get(), DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION, topic);
    ASSERT_TRUE(request) << topic;
    EXPECT_EQ(request->participant, participant) << topic;
    EXPECT_TRUE(has(readers, request->key)) << topic;
  }
  EXPECT_EQ(readers.size(), 2u);    // the request topic and the service's request
  EXPECT_EQ(writers.size(), 13u);   // every topic of the table, the reply and this one
}

// A Humble graph: Humble's rmw_dds_common Gid is 24 bytes (the GUID and 8 zeros) under the same
// type name, and its rmw_cyclonedds matches by that name. With the Humble layout the node's
// sample carries 24-byte Gids and its writer announces the ROS type name.
TEST(RosDiscoveryHumble, GidsAreTheGuidsInTwentyFourBytesUnderTheRosTypeName) {
  dds::Participant node_participant(test::dds_test_domain());
  dds::Participant graph(test::dds_test_domain());
  dds::Writer<geometry_msgs_msg_dds__PoseArray_> poses(node_participant, topics::kPoses,
                                                       &geometry_msgs_msg_dds__PoseArray__desc,
                                                       topics::latched_qos());
  const RosDiscovery discovery(node_participant, RosNode{"rangefitd", "/cell1", {}, {poses.get()}},
                               RosGidLayout::kHumble);
  ASSERT_TRUE(discovery.published());
  using Humble = rmw_dds_common_humble_msg_dds__ParticipantEntitiesInfo_;
  dds::Reader<Humble> info(graph, topics::kRosDiscovery, humble_discovery_descriptor(),
                           topics::ros_discovery_qos());
  EXPECT_EQ(type_name(info.get()), "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_");
  const auto bytes = take_bytes(info.get(), seconds(20));
  ASSERT_TRUE(bytes);
  EXPECT_EQ(bytes->size(), 4u + 24 + 4 + (4 + 7) + 1 + (4 + 10) + 2 + 4 + 4 + 2 * 24)
      << "header, Gid, one node: \"/cell1\", \"rangefitd\", padding, no reader, two writers";
  Cdr cdr{*bytes};
  const Guid participant = gid(cdr, 24);
  ASSERT_EQ(cdr.get<std::uint32_t>(), 1u);
  EXPECT_EQ(cdr.str(), "/cell1");
  EXPECT_EQ(cdr.str(), "rangefitd");
  EXPECT_TRUE(gid_seq(cdr, 24).empty());
  const std::vector<Guid> writers = gid_seq(cdr, 24);
  EXPECT_TRUE(cdr.done());
  dds_guid_t node_guid, poses_guid;
  ASSERT_EQ(dds_get_guid(node_participant.get(), &node_guid), DDS_RETCODE_OK);
  ASSERT_EQ(dds_get_guid(poses.get(), &poses_guid), DDS_RETCODE_OK);
  EXPECT_EQ(participant, guid_bytes(node_guid));
  ASSERT_EQ(writers.size(), 2u);  // the poses writer and the discovery writer itself
  EXPECT_EQ(writers[0], guid_bytes(poses_guid));
  const auto announced = discovered(graph.get(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION,
                                    topics::kRosDiscovery);
  ASSERT_TRUE(announced);
  EXPECT_EQ(announced->key, writers[1]);
  EXPECT_EQ(announced->type_name, "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_");
}

}  // namespace ros_interfaces_test
}  // namespace rangefit::daemon
