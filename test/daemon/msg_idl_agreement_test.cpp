// The rangefit_msgs .msg files (for ROS users) and daemon/idl/rangefit_msgs.idl (what we compile)
// must describe the same wire layout: same fields, same order, same types, same constants.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string read(const std::string& rel) {
  std::ifstream in(std::string(RANGEFIT_SOURCE_DIR) + "/" + rel);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

using Fields = std::vector<std::string>;  // "type name" in IDL spelling

// .msg → IDL type spelling as rosidl_adapter maps it.
std::string idl_type(std::string t) {
  static const std::map<std::string, std::string> kPrim{
      {"bool", "boolean"},  {"byte", "octet"},    {"float64", "double"},
      {"float32", "float"}, {"string", "string"}, {"uint8", "uint8"},
      {"uint32", "uint32"}, {"int32", "int32"},   {"uint64", "uint64"}};
  bool seq = false;
  if (t.size() > 2 && t.ends_with("[]")) {
    seq = true;
    t.resize(t.size() - 2);
  }
  std::string out;
  if (auto it = kPrim.find(t); it != kPrim.end()) {
    out = it->second;
  } else {
    const auto slash = t.find('/');
    out = t.substr(0, slash) + "::msg::dds_::" + t.substr(slash + 1) + "_";
  }
  return seq ? "sequence<" + out + ">" : out;
}

Fields msg_fields(const std::string& text, Fields* constants) {
  Fields out;
  std::istringstream in(text);
  std::string line;
  const std::regex field(R"(^\s*([A-Za-z0-9_/\[\]]+)\s+([a-z_0-9]+)\s*(#.*)?$)");
  const std::regex constant(R"(^\s*([a-z0-9]+)\s+([A-Z_0-9]+)\s*=\s*([0-9]+)\s*(#.*)?$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, constant)) {
      constants->push_back(idl_type(m[1]) + " " + std::string(m[2]) + " = " + std::string(m[3]));
    } else if (std::regex_match(line, m, field)) {
      out.push_back(idl_type(m[1]) + " " + std::string(m[2]));
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
  const std::regex field(R"(^\s*(.+?)\s+([a-z_0-9]+);.*$)");
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

TEST(MsgIdlAgreement, AMissingStructIsNoMatch) {
  EXPECT_TRUE(idl_struct(read("daemon/dds/idl/rangefit_msgs.idl"), "Nope_").empty());
}

}  // namespace
