// The rangefit_msgs .msg files (for ROS users) and daemon/idl/rangefit_msgs.idl (what we compile)
// must describe the same wire layout: same fields, same order, same types, same constants.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <ostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace msg_idl_agreement_test {

std::string read(const std::string& rel) {
  std::ifstream in(std::string(RANGEFIT_SOURCE_DIR) + "/" + rel);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

using Fields = std::vector<std::string>;  // "type name" in IDL spelling

// .msg → IDL type spelling as rosidl_adapter maps it; a type without a package is pkg's own.
// A fixed array T[N] is "T name[N]" in IDL: *array_suffix gets "[N]".
std::string idl_type(std::string t, const std::string& pkg = "",
                     std::string* array_suffix = nullptr) {
  static const std::map<std::string, std::string> kPrim{
      {"bool", "boolean"},  {"byte", "octet"},    {"char", "uint8"},    {"float64", "double"},
      {"float32", "float"}, {"string", "string"}, {"uint8", "uint8"},   {"int8", "int8"},
      {"uint16", "uint16"}, {"int16", "int16"},   {"uint32", "uint32"}, {"int32", "int32"},
      {"uint64", "uint64"}, {"int64", "int64"}};
  bool seq = false;
  if (t.size() > 2 && t.ends_with("[]")) {
    seq = true;
    t.resize(t.size() - 2);
  } else if (const auto open = t.find('['); open != std::string::npos && t.ends_with("]")) {
    if (array_suffix != nullptr) *array_suffix = t.substr(open);
    t.resize(open);
  }
  std::string out;
  if (auto it = kPrim.find(t); it != kPrim.end()) {
    out = it->second;
  } else if (t.starts_with("string<=")) {  // a bounded string: string<N> in IDL
    out = "string<" + t.substr(8) + ">";
  } else if (const auto slash = t.find('/'); slash != std::string::npos) {
    out = t.substr(0, slash) + "::msg::dds_::" + t.substr(slash + 1) + "_";
  } else {
    out = pkg + "::msg::dds_::" + t + "_";
  }
  return seq ? "sequence<" + out + ">" : out;
}

// The fields (and constants) of a .msg text; default values ("float64 w 1") are not part of the
// wire layout and are skipped.
Fields msg_fields(const std::string& text, Fields* constants, const std::string& pkg = "") {
  Fields out;
  std::istringstream in(text);
  std::string line;
  const std::regex field(R"(^\s*([A-Za-z0-9_/\[\]<=]+)\s+([a-z_0-9]+)(\s+[^#\s]+)?\s*(#.*)?$)");
  const std::regex constant(R"(^\s*([a-z0-9]+)\s+([A-Z_0-9]+)\s*=\s*([0-9]+)\s*(#.*)?$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, constant)) {
      constants->push_back(idl_type(m[1]) + " " + std::string(m[2]) + " = " + std::string(m[3]));
    } else if (std::regex_match(line, m, field)) {
      std::string array;
      const std::string type = idl_type(m[1], pkg, &array);
      out.push_back(type + " " + std::string(m[2]) + array);
    }
  }
  return out;
}

Fields idl_struct(const std::string& idl, const std::string& name) {
  const auto start = idl.find("struct " + name + " {");
  if (start == std::string::npos) return {};
  const auto end = idl.find("};", start);
  std::istringstream in(idl.substr(start, end - start));
  std::string line;
  std::getline(in, line);
  Fields out;
  const std::regex field(R"(^\s*(.+?)\s+([a-z_0-9]+(\[[0-9]+\])?);.*$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, field))
      out.push_back(std::string(m[1]) + " " + std::string(m[2]));
  }
  return out;
}

Fields idl_constants(const std::string& idl, const std::string& name) {
  Fields out;
  const auto start = idl.find("module " + name + "_Constants {");
  if (start == std::string::npos) return out;
  std::istringstream in(idl.substr(start, idl.find("};", start) - start));
  std::string line;
  const std::regex constant(R"(^\s*const\s+(\S+)\s+([A-Z_0-9]+)\s*=\s*([0-9]+);.*$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, constant)) {
      out.push_back(std::string(m[1]) + " " + std::string(m[2]) + " = " + std::string(m[3]));
    }
  }
  return out;
}

class MsgIdlAgreement : public ::testing::TestWithParam<const char*> {};

TEST_P(MsgIdlAgreement, MsgAndIdlDeclareTheSameFieldsInOrder) {
  const std::string name = GetParam();
  Fields msg_constants;
  const Fields msg =
      msg_fields(read("daemon/dds/msg/rangefit_msgs/msg/" + name + ".msg"), &msg_constants);
  const std::string idl = read("daemon/dds/idl/rangefit_msgs.idl");
  ASSERT_FALSE(msg.empty());
  EXPECT_EQ(msg, idl_struct(idl, name + "_"));
  EXPECT_EQ(msg_constants, idl_constants(idl, name));
}

INSTANTIATE_TEST_SUITE_P(RangefitMsgs, MsgIdlAgreement,
                         ::testing::Values("Detection", "DetectRequest", "State", "Models"));

// The ROS 2 service /rangefit/detect carries the topic types after rmw_cyclonedds's call header
// (daemon/dds/service_body.hpp copies the body as one block, so the order must agree too).
TEST(MsgIdlAgreement, ServiceTypesAreTheTopicTypesAfterTheCallHeader) {
  const std::string srvs = read("daemon/dds/idl/rangefit_srvs.idl");
  const std::string msgs = read("daemon/dds/idl/rangefit_msgs.idl");
  const Fields header{"uint64 rmw_client_guid", "int64 rmw_sequence_number"};
  for (const auto& [service, topic] : {std::pair{"Detect_Request_", "DetectRequest_"},
                                       std::pair{"Detect_Response_", "Detection_"}}) {
    Fields expected = header;
    const Fields body = idl_struct(msgs, topic);
    ASSERT_FALSE(body.empty()) << topic;
    expected.insert(expected.end(), body.begin(), body.end());
    EXPECT_EQ(idl_struct(srvs, service), expected) << service << " vs " << topic;
  }
}

TEST(MsgIdlAgreement, AMissingStructIsNoMatch) {
  EXPECT_TRUE(idl_struct(read("daemon/dds/idl/rangefit_msgs.idl"), "Nope_").empty());
}

// The standard ROS 2 types we compile ourselves must be the official ones, field for field: the
// field and constant lines of the official .msg files (comments and blank lines left out), from
// ros2/common_interfaces (branch humble; jazzy has the same fields, and Marker one more constant,
// ARROW_STRIP = 12), ros-perception/vision_msgs (tags 4.0.0 to 4.1.1, all the same) and
// ros2/rcl_interfaces (builtin_interfaces) and ros2/rmw_dds_common (the graph's discovery info).
struct Official {
  const char* pkg;
  const char* name;
  const char* idl_file;  // in daemon/dds/idl
  const char* msg;       // the official text
};

const Official kOfficial[] = {
    {"builtin_interfaces", "Time", "builtin_interfaces.idl", "int32 sec\nuint32 nanosec\n"},
    {"builtin_interfaces", "Duration", "builtin_interfaces.idl", "int32 sec\nuint32 nanosec\n"},
    {"std_msgs", "Header", "std_msgs.idl", "builtin_interfaces/Time stamp\nstring frame_id\n"},
    {"std_msgs", "ColorRGBA", "std_msgs.idl", "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n"},
    {"geometry_msgs", "Point", "geometry_msgs.idl", "float64 x\nfloat64 y\nfloat64 z\n"},
    {"geometry_msgs", "Vector3", "geometry_msgs.idl", "float64 x\nfloat64 y\nfloat64 z\n"},
    {"geometry_msgs", "Quaternion", "geometry_msgs.idl",
     "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"},
    {"geometry_msgs", "Pose", "geometry_msgs.idl", "Point position\nQuaternion orientation\n"},
    {"geometry_msgs", "PoseWithCovariance", "geometry_msgs.idl",
     "Pose pose\nfloat64[36] covariance\n"},
    {"geometry_msgs", "PoseStamped", "geometry_msgs.idl", "std_msgs/Header header\nPose pose\n"},
    {"geometry_msgs", "PoseArray", "geometry_msgs.idl", "std_msgs/Header header\nPose[] poses\n"},
    {"geometry_msgs", "Transform", "geometry_msgs.idl",
     "Vector3 translation\nQuaternion rotation\n"},
    {"geometry_msgs", "TransformStamped", "geometry_msgs.idl",
     "std_msgs/Header header\nstring child_frame_id\nTransform transform\n"},
    {"sensor_msgs", "CompressedImage", "sensor_msgs.idl",
     "std_msgs/Header header # Header timestamp should be acquisition time of image\n"
     "string format                # Specifies the format of the data\n"
     "uint8[] data                 # Compressed image buffer\n"},
    {"sensor_msgs", "PointCloud2", "sensor_msgs.idl",
     "std_msgs/Header header\nuint32 height\nuint32 width\nPointField[] fields\n"
     "bool    is_bigendian\nuint32  point_step\nuint32  row_step\nuint8[] data\nbool is_dense\n"},
    {"vision_msgs", "ObjectHypothesis", "vision_msgs.idl", "string class_id\nfloat64 score\n"},
    {"vision_msgs", "ObjectHypothesisWithPose", "vision_msgs.idl",
     "ObjectHypothesis hypothesis\ngeometry_msgs/PoseWithCovariance pose\n"},
    {"vision_msgs", "BoundingBox3D", "vision_msgs.idl",
     "geometry_msgs/Pose center\ngeometry_msgs/Vector3 size\n"},
    {"vision_msgs", "Detection3D", "vision_msgs.idl",
     "std_msgs/Header header\nObjectHypothesisWithPose[] results\nBoundingBox3D bbox\n"
     "string id\n"},
    {"vision_msgs", "Detection3DArray", "vision_msgs.idl",
     "std_msgs/Header header\nDetection3D[] detections\n"},
    {"visualization_msgs", "UVCoordinate", "visualization_msgs.idl", "float32 u\nfloat32 v\n"},
    {"visualization_msgs", "MeshFile", "visualization_msgs.idl", "string filename\nuint8[] data\n"},
    {"visualization_msgs", "Marker", "visualization_msgs.idl",
     "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\nint32 LINE_STRIP=4\n"
     "int32 LINE_LIST=5\nint32 CUBE_LIST=6\nint32 SPHERE_LIST=7\nint32 POINTS=8\n"
     "int32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\nint32 TRIANGLE_LIST=11\n"
     "int32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\nint32 DELETEALL=3\n"
     "std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\n"
     "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\n"
     "builtin_interfaces/Duration lifetime\nbool frame_locked\n"
     "geometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\nstring texture_resource\n"
     "sensor_msgs/CompressedImage texture\nUVCoordinate[] uv_coordinates\nstring text\n"
     "string mesh_resource\nMeshFile mesh_file\nbool mesh_use_embedded_materials\n"},
    {"visualization_msgs", "MarkerArray", "visualization_msgs.idl", "Marker[] markers\n"},
    // ros2/rmw_dds_common, branch jazzy (the Gid of Iron and later; Humble's is char[24]).
    {"rmw_dds_common", "Gid", "rmw_dds_common.idl", "char[16] data\n"},
    {"rmw_dds_common", "NodeEntitiesInfo", "rmw_dds_common.idl",
     "string<=256 node_namespace\nstring<=256 node_name\nGid[] reader_gid_seq\n"
     "Gid[] writer_gid_seq\n"},
    {"rmw_dds_common", "ParticipantEntitiesInfo", "rmw_dds_common.idl",
     "Gid gid\nNodeEntitiesInfo[] node_entities_info_seq\n"},
    // ros2/rmw_dds_common, branch humble, in the module of rmw_dds_common_humble.idl.
    {"rmw_dds_common_humble", "Gid", "rmw_dds_common_humble.idl", "char[24] data\n"},
    {"rmw_dds_common_humble", "NodeEntitiesInfo", "rmw_dds_common_humble.idl",
     "string<=256 node_namespace\nstring<=256 node_name\nGid[] reader_gid_seq\n"
     "Gid[] writer_gid_seq\n"},
    {"rmw_dds_common_humble", "ParticipantEntitiesInfo", "rmw_dds_common_humble.idl",
     "Gid gid\nNodeEntitiesInfo[] node_entities_info_seq\n"},
};

void PrintTo(const Official& o, std::ostream* os) { *os << o.pkg << "/" << o.name; }

class OfficialDefinition : public ::testing::TestWithParam<Official> {};

TEST_P(OfficialDefinition, OurIdlDeclaresTheOfficialFieldsInOrder) {
  const Official& o = GetParam();
  Fields constants;
  const Fields msg = msg_fields(o.msg, &constants, o.pkg);
  const std::string idl = read(std::string("daemon/dds/idl/") + o.idl_file);
  ASSERT_FALSE(msg.empty());
  EXPECT_EQ(msg, idl_struct(idl, std::string(o.name) + "_")) << o.pkg << "/" << o.name;
  if (!constants.empty()) {
    EXPECT_EQ(constants, idl_constants(idl, o.name));
  }
}

INSTANTIATE_TEST_SUITE_P(Ros2, OfficialDefinition, ::testing::ValuesIn(kOfficial),
                         [](const auto& p) {
                           return std::string(p.param.pkg) + "_" + p.param.name;
                         });

// The parser must be able to fail: a field out of order, a missing fixed array size and a
// sequence taken for a single value are all differences.
TEST(OfficialDefinition, AReorderedOrResizedFieldIsNoMatch) {
  const std::string idl = read("daemon/dds/idl/geometry_msgs.idl");
  Fields c;
  EXPECT_NE(msg_fields("float64[36] covariance\nPose pose\n", &c, "geometry_msgs"),
            idl_struct(idl, "PoseWithCovariance_"));
  EXPECT_NE(msg_fields("Pose pose\nfloat64[9] covariance\n", &c, "geometry_msgs"),
            idl_struct(idl, "PoseWithCovariance_"));
  EXPECT_NE(msg_fields("std_msgs/Header header\nPose poses\n", &c, "geometry_msgs"),
            idl_struct(idl, "PoseArray_"));
}

}  // namespace msg_idl_agreement_test
