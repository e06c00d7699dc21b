// What rviz2 and vision_msgs users receive from rangefitd for a result, decoded from the raw XCDR1
// samples: on rt/rangefit/markers a DELETEALL and one TRIANGLE_LIST mesh per part whose vertices
// lie on the fitted surface (the bore's wall, the model part's superquadric), on
// rt/rangefit/detections3d one Detection3D per part whose pose is the one on rt/rangefit/poses
// and on rt/tf, all stamped with the acquisition time.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "daemon/dds/dds_service.hpp"
#include "detect/object/superquadric.hpp"
#include "test/daemon/dds_test_env.hpp"
#include "test/daemon/xcdr_reader.hpp"

namespace rangefit::daemon {
namespace ros_detections_test {
using std::chrono::milliseconds;
using std::chrono::seconds;
using test::Cdr;
using test::take_bytes;

constexpr std::int64_t kAcquired = 1'700'000'123'456'789'012;  // ns since the epoch

struct Stamp {
  std::int32_t sec;
  std::uint32_t nanosec;
};
Stamp read_stamp(Cdr& c) { return {c.get<std::int32_t>(), c.get<std::uint32_t>()}; }
void expect_acquisition_stamp(const Stamp& s) {
  EXPECT_EQ(s.sec, kAcquired / 1'000'000'000);
  EXPECT_EQ(s.nanosec, kAcquired % 1'000'000'000);
}

Eigen::Isometry3d read_pose(Cdr& c) {  // geometry_msgs/Pose, metres → mm
  Eigen::Vector3d t;
  for (int k = 0; k < 3; ++k) t[k] = c.get<double>() * 1e3;
  const double x = c.get<double>(), y = c.get<double>(), z = c.get<double>(), w = c.get<double>();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(w, x, y, z).toRotationMatrix();
  T.translation() = t;
  return T;
}
Eigen::Vector3d read_vector(Cdr& c) {
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) v[k] = c.get<double>();
  return v;
}

void expect_same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  EXPECT_LT((a.translation() - b.translation()).norm(), 1e-9);
  EXPECT_LT((a.linear() - b.linear()).norm(), 1e-9);
}

struct Marker {
  std::string frame, ns;
  Stamp stamp{};
  std::int32_t id = 0, type = 0, action = 0;
  Eigen::Isometry3d pose;
  Eigen::Vector3d scale;
  std::vector<Eigen::Vector3d> points;  // as sent: metres, marker frame
};

std::vector<Marker> read_markers(const std::vector<unsigned char>& bytes) {
  Cdr c{bytes};
  std::vector<Marker> out(c.get<std::uint32_t>());
  for (Marker& m : out) {
    m.stamp = read_stamp(c);
    m.frame = c.str();
    m.ns = c.str();
    m.id = c.get<std::int32_t>();
    m.type = c.get<std::int32_t>();
    m.action = c.get<std::int32_t>();
    m.pose = read_pose(c);
    m.scale = read_vector(c);
    for (int k = 0; k < 4; ++k) c.get<float>();  // colour
    c.get<std::int32_t>();                       // lifetime
    c.get<std::uint32_t>();
    EXPECT_EQ(c.get<std::uint8_t>(), 0) << "frame_locked";
    m.points.resize(c.get<std::uint32_t>());
    for (auto& p : m.points) p = read_vector(c);
    EXPECT_EQ(c.get<std::uint32_t>(), 0u) << "colors";
    EXPECT_EQ(c.str(), "") << "texture_resource";
    read_stamp(c);  // texture: sensor_msgs/CompressedImage
    EXPECT_EQ(c.str(), "") << "texture.header.frame_id";
    EXPECT_EQ(c.str(), "") << "texture.format";
    EXPECT_TRUE(c.octets().empty());
    EXPECT_EQ(c.get<std::uint32_t>(), 0u) << "uv_coordinates";
    EXPECT_EQ(c.str(), "") << "text";
    EXPECT_EQ(c.str(), "") << "mesh_resource";
    EXPECT_EQ(c.str(), "") << "mesh_file.filename";
    EXPECT_TRUE(c.octets().empty());
    EXPECT_EQ(c.get<std::uint8_t>(), 0) << "mesh_use_embedded_materials";
  }
  EXPECT_TRUE(c.done()) << "bytes left after the last marker";
  return out;
}

struct Detection3D {
  std::string frame, class_id, id;
  Stamp stamp{};
  double score = 0;
  Eigen::Isometry3d pose, box;
  Eigen::Vector3d size;  // metres
};

std::vector<Detection3D> read_detections(const std::vector<unsigned char>& bytes,
                                         Stamp* stamp = nullptr, std::string* frame = nullptr) {
  Cdr c{bytes};
  const Stamp s = read_stamp(c);
  const std::string f = c.str();
  if (stamp != nullptr) *stamp = s;
  if (frame != nullptr) *frame = f;
  std::vector<Detection3D> out(c.get<std::uint32_t>());
  for (Detection3D& d : out) {
    d.stamp = read_stamp(c);
    d.frame = c.str();
    EXPECT_EQ(c.get<std::uint32_t>(), 1u) << "one hypothesis per detection";
    d.class_id = c.str();
    d.score = c.get<double>();
    d.pose = read_pose(c);
    for (int k = 0; k < 36; ++k) c.get<double>();  // covariance
    d.box = read_pose(c);
    d.size = read_vector(c);
    d.id = c.str();
  }
  EXPECT_TRUE(c.done()) << "bytes left after the last detection";
  return out;
}

class RosDetectionsTest : public ::testing::Test {
 protected:
  RosDetectionsTest() {
    config_.dds.domain_id = test::dds_test_domain();
    config_.frames.world = "cell_base";
    ObjectModelConfig mallet;
    mallet.name = "mallet";
    mallet.model.name = "mallet";
    mallet.model.parts = {{"head", {20, 25, 45, 0.3, 0.8, 0, 0}},
                          {"shaft", {6, 7, 80, 0.6, 1.0, 0.3, -0.2}}};  // tapered
    config_.objects.push_back(mallet);
    service_ = std::make_unique<DdsService>(config_.dds);
    service_->publish_frames(config_);
  }

  template <class T>
  std::unique_ptr<dds::Reader<T>> reader(const dds::Topic<T>& t) {
    return std::make_unique<dds::Reader<T>>(participant_, t);
  }
  static bool wait_matched(int n, const std::function<int()>& matched) {
    for (int i = 0; i < 2000 && matched() < n; ++i) std::this_thread::sleep_for(milliseconds(5));
    return matched() >= n;
  }

  static Eigen::Isometry3d pose(const Eigen::Vector3d& axis, double angle,
                                const Eigen::Vector3d& t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
    T.translation() = t;
    return T;
  }

  DetectionResult mallet_result() const {
    DetectionResult r;
    r.request_id = "m";
    r.kind = DetectKind::kObject;
    r.model = "mallet";
    r.found = true;
    r.parts = {{"head", pose({1, 2, 3}, 0.7, {120, -40, 35}), 0.9, 0},
               {"shaft", pose({0, 1, 0}, 1.2, {40, -40, 20}), 0.8, 0}};
    r.acquired_wall_ns = kAcquired;
    return r;
  }

  DaemonConfig config_;
  std::unique_ptr<DdsService> service_;
  dds::Participant participant_{test::dds_test_domain()};
};

TEST_F(RosDetectionsTest, MalletPartsAreSuperquadricMeshesWhoseVerticesLieOnTheFittedSurface) {
  const DetectionResult r = mallet_result();
  service_->on_result(r);
  auto markers = reader(topics::markers());
  EXPECT_EQ(test::type_name(markers->get()), "visualization_msgs::msg::dds_::MarkerArray_");
  const auto bytes = take_bytes(markers->get(), seconds(20));
  ASSERT_TRUE(bytes);
  const auto m = read_markers(*bytes);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].action, 3) << "DELETEALL first: nothing of an earlier result stays";
  EXPECT_EQ(m[0].ns, "rangefit");
  for (std::size_t i = 0; i < 2; ++i) {
    const Marker& mk = m[i + 1];
    const Superquadric& sq = config_.objects[0].model.parts[i].shape;
    EXPECT_EQ(mk.type, 11) << "TRIANGLE_LIST";
    EXPECT_EQ(mk.action, 0) << "ADD";
    EXPECT_EQ(mk.ns, "rangefit");
    EXPECT_EQ(mk.frame, "cell_base");
    expect_acquisition_stamp(mk.stamp);
    EXPECT_EQ(mk.scale, Eigen::Vector3d(1, 1, 1));
    ASSERT_GE(mk.points.size(), 300u);
    EXPECT_EQ(mk.points.size() % 3, 0u);
    for (const auto& p : mk.points) {
      // Where rviz2 draws the vertex (marker pose applied), brought into the fitted part's frame.
      const Eigen::Vector3d world_mm = mk.pose * (p * 1e3);
      const Eigen::Vector3d in_part = r.parts[i].T_world_part.inverse() * world_mm;
      ASSERT_NEAR(inside_outside(sq, in_part), 1.0, 1e-6) << r.parts[i].name;
    }
  }
}

TEST_F(RosDetectionsTest, BoreIsAnOpenTubeOfTheFittedRadiusIntoThePart) {
  DetectionResult r;
  r.request_id = "b";
  r.kind = DetectKind::kBore;
  r.found = true;
  r.bore_radius_mm = 6.0;
  r.parts = {{"bore", pose({1, -1, 0.2}, 0.4, {10, 20, 285.8}), 0.95, 0}};
  r.acquired_wall_ns = kAcquired;
  service_->on_result(r);
  auto markers = reader(topics::markers());
  const auto bytes = take_bytes(markers->get(), seconds(20));
  ASSERT_TRUE(bytes);
  const auto m = read_markers(*bytes);
  ASSERT_EQ(m.size(), 2u);
  const Eigen::Vector3d entrance = r.parts[0].T_world_part.translation();
  const Eigen::Vector3d axis = r.parts[0].T_world_part.linear().col(2);  // out of the bore
  ASSERT_GE(m[1].points.size(), 96u);
  double deepest = 0;
  for (const auto& p : m[1].points) {
    const Eigen::Vector3d d = m[1].pose * (p * 1e3) - entrance;
    const double along = d.dot(axis);
    ASSERT_NEAR((d - along * axis).norm(), 6.0, 0.1) << "off the bore's wall";
    ASSERT_LE(along, 1e-9) << "the wall goes into the part, not out toward the sensor";
    deepest = std::min(deepest, along);
  }
  EXPECT_NEAR(deepest, -12.0, 1e-9);  // two radii

  auto detections = reader(topics::detections3d());
  const auto dbytes = take_bytes(detections->get(), seconds(20));
  ASSERT_TRUE(dbytes);
  const auto d = read_detections(*dbytes);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].class_id, "bore");
  EXPECT_NEAR((d[0].size - Eigen::Vector3d(0.012, 0.012, 0.012)).norm(), 0, 1e-12);
  EXPECT_LT((d[0].box.translation() - (entrance - 6.0 * axis)).norm(), 1e-9)
      << "the box is centred on the wall's middle";
}

TEST_F(RosDetectionsTest, DetectionPoseIsThePoseOnPosesAndTheTfFrame) {
  auto tf = reader(topics::tf());
  ASSERT_TRUE(wait_matched(1, [&] { return tf->matched(); }));
  const DetectionResult r = mallet_result();
  service_->on_result(r);
  auto detections = reader(topics::detections3d());
  auto poses = reader(topics::poses());
  EXPECT_EQ(test::type_name(detections->get()), "vision_msgs::msg::dds_::Detection3DArray_");
  const auto dbytes = take_bytes(detections->get(), seconds(20));
  const auto pbytes = take_bytes(poses->get(), seconds(20));
  const auto tbytes = take_bytes(tf->get(), seconds(20));
  ASSERT_TRUE(dbytes && pbytes && tbytes);

  Stamp stamp{};
  std::string frame;
  const auto d = read_detections(*dbytes, &stamp, &frame);
  expect_acquisition_stamp(stamp);
  EXPECT_EQ(frame, "cell_base");
  ASSERT_EQ(d.size(), 2u);

  Cdr p{*pbytes};
  read_stamp(p);
  EXPECT_EQ(p.str(), "cell_base");
  ASSERT_EQ(p.get<std::uint32_t>(), 2u);
  Cdr t{*tbytes};
  ASSERT_EQ(t.get<std::uint32_t>(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    expect_acquisition_stamp(d[i].stamp);
    EXPECT_EQ(d[i].frame, "cell_base");
    EXPECT_EQ(d[i].class_id, "mallet");
    EXPECT_DOUBLE_EQ(d[i].score, r.parts[i].score);
    EXPECT_EQ(d[i].id, "rangefit/mallet/" + r.parts[i].name + "/0") << "the part's TF frame";
    expect_same_pose(d[i].pose, r.parts[i].T_world_part);
    expect_same_pose(d[i].pose, read_pose(p));
    expect_acquisition_stamp(read_stamp(t));
    EXPECT_EQ(t.str(), "cell_base");
    EXPECT_EQ(t.str(), d[i].id);
    expect_same_pose(d[i].pose, read_pose(t));  // Transform has Pose's layout
  }
  // The head is untapered: its box is its full size, centred on it, in the part's axes.
  EXPECT_NEAR((d[0].size - Eigen::Vector3d(0.040, 0.050, 0.090)).norm(), 0, 1e-12);
  expect_same_pose(d[0].box, r.parts[0].T_world_part);
  // The shaft is tapered, its box still spans its length from pole to pole.
  EXPECT_NEAR(d[1].size.z(), 0.160, 1e-12);
}

TEST_F(RosDetectionsTest, NothingFoundClearsTheMarkersAndSendsNoDetections) {
  DetectionResult r;
  r.request_id = "n";
  r.kind = DetectKind::kObject;
  r.model = "mallet";
  r.reason = "not found";
  r.acquired_wall_ns = kAcquired;
  service_->on_result(r);
  auto markers = reader(topics::markers());
  auto detections = reader(topics::detections3d());
  const auto mbytes = take_bytes(markers->get(), seconds(20));
  const auto dbytes = take_bytes(detections->get(), seconds(20));
  ASSERT_TRUE(mbytes && dbytes);
  const auto m = read_markers(*mbytes);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].action, 3);
  EXPECT_TRUE(read_detections(*dbytes).empty());
}

TEST_F(RosDetectionsTest, APartOfAnUnknownModelGetsNoMeshAndAnEmptyBox) {
  DetectionResult r = mallet_result();
  r.model = "removed_by_a_reload";
  service_->on_result(r);
  auto markers = reader(topics::markers());
  auto detections = reader(topics::detections3d());
  const auto mbytes = take_bytes(markers->get(), seconds(20));
  const auto dbytes = take_bytes(detections->get(), seconds(20));
  ASSERT_TRUE(mbytes && dbytes);
  EXPECT_EQ(read_markers(*mbytes).size(), 1u);
  const auto d = read_detections(*dbytes);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].size, Eigen::Vector3d::Zero());
  expect_same_pose(d[0].pose, r.parts[0].T_world_part);
}

}  // namespace ros_detections_test
}  // namespace rangefit::daemon
