// The ROS 2 side of the configuration: [frames] names the world and sensor frames (checked as
// tf2 frame ids), ROS_DOMAIN_ID picks the domain when the config names none, [ros] namespace and
// [dds] partition separate cells (checked as ROS namespaces and plain partition names), [ros]
// distro (else ROS_DISTRO) picks the ROS 2 release's discovery layout.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <string>

#include "daemon/service/config.hpp"

namespace rangefit::daemon {
namespace ros_config_test {

const std::string kDevice =
    "[[devices]]\nname = \"css\"\nkind = \"css\"\ndriver = \"replay\"\nreplay_file = \"x.ply\"\n";

// Sets (or, with nullptr, clears) an environment variable for one test.
class EnvVar {
 public:
  EnvVar(const char* name, const char* value) : name_(name) {
    if (value == nullptr) {
      unsetenv(name);
    } else {
      setenv(name, value, 1);
    }
  }
  ~EnvVar() { unsetenv(name_); }
  EnvVar(const EnvVar&) = delete;
  EnvVar& operator=(const EnvVar&) = delete;

 private:
  const char* name_;
};

struct RosDomainEnv : EnvVar {
  explicit RosDomainEnv(const char* value) : EnvVar("ROS_DOMAIN_ID", value) {}
};
struct RosDistroEnv : EnvVar {
  explicit RosDistroEnv(const char* value) : EnvVar("ROS_DISTRO", value) {}
};

TEST(RosConfig, DistroComesFromTheConfigElseRosDistroElseJazzy) {
  {
    RosDistroEnv env(nullptr);
    auto plain = parse_config(kDevice);
    ASSERT_TRUE(plain.config) << plain.error;
    EXPECT_EQ(plain.config->dds.ros_distro, "jazzy");
  }
  RosDistroEnv env("humble");
  auto from_env = parse_config(kDevice);
  ASSERT_TRUE(from_env.config) << from_env.error;
  EXPECT_EQ(from_env.config->dds.ros_distro, "humble");
  auto from_config = parse_config(kDevice + "[ros]\ndistro = \"kilted\"\n");
  ASSERT_TRUE(from_config.config) << from_config.error;
  EXPECT_EQ(from_config.config->dds.ros_distro, "kilted");
}

TEST(RosConfig, AnUnknownDistroIsAnErrorNamingTheKnownOnes) {
  RosDistroEnv clear(nullptr);
  auto typo = parse_config(kDevice + "[ros]\ndistro = \"humbel\"\n");
  EXPECT_FALSE(typo.config);
  EXPECT_NE(typo.error.find("ros.distro"), std::string::npos) << typo.error;
  EXPECT_NE(typo.error.find("humble, iron, jazzy, kilted, rolling"), std::string::npos)
      << typo.error;
  RosDistroEnv env("foxy");
  auto from_env = parse_config(kDevice);
  EXPECT_FALSE(from_env.config);
  EXPECT_NE(from_env.error.find("ROS_DISTRO"), std::string::npos) << from_env.error;
}

TEST(RosConfig, FramesNameTheWorldAndEachSensorAndDefaultToWorldAndTheDeviceName) {
  auto plain = parse_config(kDevice);
  ASSERT_TRUE(plain.config) << plain.error;
  EXPECT_EQ(plain.config->frames.world, "world");
  EXPECT_EQ(plain.config->frames.sensor("css"), "css");
  auto named = parse_config(kDevice + "[frames]\nworld = \"base_link\"\ncss = \"css_link\"\n");
  ASSERT_TRUE(named.config) << named.error;
  EXPECT_EQ(named.config->frames.world, "base_link");
  EXPECT_EQ(named.config->frames.sensor("css"), "css_link");
}

TEST(RosConfig, BadFrameIdsAndUnknownSensorsAreErrorsNamingTheField) {
  auto slash = parse_config(kDevice + "[frames]\nworld = \"/world\"\n");
  EXPECT_FALSE(slash.config);
  EXPECT_NE(slash.error.find("frames.world"), std::string::npos) << slash.error;
  auto space = parse_config(kDevice + "[frames]\ncss = \"css link\"\n");
  EXPECT_FALSE(space.config);
  EXPECT_NE(space.error.find("frames.css"), std::string::npos) << space.error;
  auto unknown = parse_config(kDevice + "[frames]\nlidar = \"lidar\"\n");
  EXPECT_FALSE(unknown.config);
  EXPECT_NE(unknown.error.find("neither world nor a device"), std::string::npos) << unknown.error;
}

TEST(RosConfig, RosDomainIdIsTheDomainWhenTheConfigSetsNone) {
  RosDomainEnv env("17");
  auto from_env = parse_config(kDevice);
  ASSERT_TRUE(from_env.config) << from_env.error;
  EXPECT_EQ(from_env.config->dds.domain_id, 17u);
  auto from_config = parse_config(kDevice + "[dds]\ndomain_id = 3\n");
  ASSERT_TRUE(from_config.config) << from_config.error;
  EXPECT_EQ(from_config.config->dds.domain_id, 3u);
}

TEST(RosConfig, UnsetRosDomainIdMeansDomainZeroAndABadOneIsAnError) {
  {
    RosDomainEnv env(nullptr);
    auto none = parse_config(kDevice);
    ASSERT_TRUE(none.config) << none.error;
    EXPECT_EQ(none.config->dds.domain_id, 0u);
  }
  for (const char* bad : {"abc", "233", "-1", "99999999999"}) {
    RosDomainEnv env(bad);
    auto r = parse_config(kDevice);
    EXPECT_FALSE(r.config) << bad;
    EXPECT_NE(r.error.find("ROS_DOMAIN_ID"), std::string::npos) << r.error;
  }
}

TEST(RosConfig, NamespaceAndPartitionAreReadAndDefaultToNone) {
  auto plain = parse_config(kDevice);
  ASSERT_TRUE(plain.config) << plain.error;
  EXPECT_EQ(plain.config->dds.ros_namespace, "");
  EXPECT_EQ(plain.config->dds.partition, "");
  auto set = parse_config(kDevice +
                          "[ros]\nnamespace = \"/plant/cell_1\"\n[dds]\npartition = \"cell-1\"\n");
  ASSERT_TRUE(set.config) << set.error;
  EXPECT_EQ(set.config->dds.ros_namespace, "plant/cell_1") << "the leading '/' is dropped";
  EXPECT_EQ(set.config->dds.partition, "cell-1");
}

TEST(RosConfig, BadNamespacesAndPartitionsAreErrorsNamingTheField) {
  for (const char* bad : {"cell 1", "1cell", "cell//one", "cell/", "cell/2nd", "zelle-1"}) {
    auto r = parse_config(kDevice + "[ros]\nnamespace = \"" + bad + "\"\n");
    EXPECT_FALSE(r.config) << bad;
    EXPECT_NE(r.error.find("ros.namespace"), std::string::npos) << r.error;
  }
  for (const char* bad : {"cell*", "cell one", "a?b"}) {
    auto r = parse_config(kDevice + "[dds]\npartition = \"" + bad + "\"\n");
    EXPECT_FALSE(r.config) << bad;
    EXPECT_NE(r.error.find("dds.partition"), std::string::npos) << r.error;
  }
  auto unknown = parse_config(kDevice + "[ros]\nname_space = \"x\"\n");
  EXPECT_FALSE(unknown.config);
}

}  // namespace ros_config_test
}  // namespace rangefit::daemon
