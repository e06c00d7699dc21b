#include "daemon/service/address_check.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace rangefit::daemon {
namespace address_check_test {

IpAllowList list(const char* text) {
  std::string why;
  const auto l = parse_ip_allow(text, &why);
  EXPECT_TRUE(l) << why;
  return l.value_or(IpAllowList{});
}

// The unit's default list (cmake/packaging.cmake).
const char* kDefault =
    "localhost link-local multicast 10.0.0.0/8 172.16.0.0/12 192.168.0.0/16 fc00::/7";

TEST(IpAllow, KeywordsAndPrefixesAsSystemdReadsThem) {
  const IpAllowList l = list(kDefault);
  for (const char* inside :
       {"127.0.0.1", "127.1.2.3", "::1", "169.254.7.7", "fe80::1", "239.255.0.1", "ff02::1",
        "10.20.30.40", "172.31.255.255", "192.168.1.5", "fd12:3456::1"}) {
    EXPECT_TRUE(ip_allowed(l, inside)) << inside;
  }
  for (const char* outside : {"8.8.8.8", "172.32.0.1", "192.169.0.1", "11.0.0.1", "::2",
                              "2001:db8::1", "0.0.0.0", "::", "localhost", "", "1.2.3"}) {
    EXPECT_FALSE(ip_allowed(l, outside)) << outside;
  }
}

TEST(IpAllow, TheWildcardAddressNeedsAny) {
  EXPECT_FALSE(ip_allowed(list("0.0.0.0/1 128.0.0.0/1"), "0.0.0.0"));  // all, but not "any"
  EXPECT_TRUE(ip_allowed(list("any"), "0.0.0.0"));
  EXPECT_TRUE(ip_allowed(list("any"), "::"));
  EXPECT_TRUE(ip_allowed(list("0.0.0.0/0"), "0.0.0.0"));
  EXPECT_FALSE(ip_allowed(list("0.0.0.0/0"), "::"));
  EXPECT_TRUE(ip_allowed(list("any"), "203.0.113.9"));
}

TEST(IpAllow, APrefixCutsInsideAByte) {
  const IpAllowList l = list("192.168.4.0/22 2001:db8:80::/41");
  EXPECT_TRUE(ip_allowed(l, "192.168.7.255"));
  EXPECT_FALSE(ip_allowed(l, "192.168.8.0"));
  EXPECT_FALSE(ip_allowed(l, "192.168.3.255"));
  EXPECT_TRUE(ip_allowed(l, "2001:db8:ff::1"));
  EXPECT_FALSE(ip_allowed(l, "2001:db8:7f::1"));
  EXPECT_TRUE(ip_allowed(list("10.0.0.7"), "10.0.0.7"));  // a bare address: itself only
  EXPECT_FALSE(ip_allowed(list("10.0.0.7"), "10.0.0.8"));
}

TEST(IpAllow, AnEmptyListAllowsNothingAndBadWordsAreNamed) {
  EXPECT_FALSE(ip_allowed(list(""), "127.0.0.1"));
  for (const char* bad :
       {"localhost 10.0.0.0/33", "10.0.0.0/", "10.0.0.0/x", "lan", "::1/129", "10.0.0.0/8/8"}) {
    std::string why;
    EXPECT_FALSE(parse_ip_allow(bad, &why)) << bad;
    EXPECT_NE(why.find("IPAddressAllow"), std::string::npos) << why;
  }
}

TEST(IpAllow, TheBuiltListParses) {
  // What rangefitd compares with: the unit's list from the same CMake variable.
  EXPECT_NO_THROW(built_ip_allow());
  EXPECT_EQ(built_ip_allow().text, RANGEFITD_IP_ADDRESS_ALLOW);
}

DaemonConfig with_listen(const char* http, const char* tcp = "") {
  DaemonConfig c;
  c.http.listen = http;
  c.tcp.listen = tcp;
  return c;
}

std::vector<std::string> no_interfaces(const std::string&) { return {}; }

TEST(AddressCheck, ListenAddressesInsideTheListPass) {
  const IpAllowList l = list(kDefault);
  EXPECT_EQ(
      check_allowed_addresses(with_listen("127.0.0.1:8080", "localhost:8081"), l, no_interfaces),
      "");
  EXPECT_EQ(check_allowed_addresses(with_listen("192.168.10.2:80"), l, no_interfaces), "");
  EXPECT_EQ(check_allowed_addresses(with_listen(""), l, no_interfaces), "");  // both off
}

TEST(AddressCheck, ListenAddressOutsideTheListIsRefusedNamingFieldAndList) {
  const IpAllowList l = list(kDefault);
  const std::string why =
      check_allowed_addresses(with_listen("127.0.0.1:8080", "203.0.113.5:9000"), l, no_interfaces);
  EXPECT_NE(why.find("tcp.listen \"203.0.113.5:9000\""), std::string::npos) << why;
  EXPECT_NE(why.find(kDefault), std::string::npos) << why;
  EXPECT_NE(why.find("IPAddressAllow"), std::string::npos) << why;
}

TEST(AddressCheck, EveryAddressIsRefusedUnlessTheListIsAny) {
  const std::string why =
      check_allowed_addresses(with_listen("0.0.0.0:8080"), list(kDefault), no_interfaces);
  EXPECT_NE(why.find("http.listen \"0.0.0.0:8080\""), std::string::npos) << why;
  EXPECT_NE(why.find("every address"), std::string::npos) << why;
  EXPECT_EQ(check_allowed_addresses(with_listen("0.0.0.0:8080"), list("any"), no_interfaces), "");
  // Loopback only: the private ranges are out too.
  EXPECT_NE(check_allowed_addresses(with_listen("10.1.1.1:80"), list("localhost"), no_interfaces),
            "");
}

TEST(DdsAddresses, InterfacesAndPeersOfACycloneConfiguration) {
  const DdsAddresses a = dds_addresses(R"(<CycloneDDS><Domain><General><Interfaces>
      <NetworkInterface address="192.168.3.4" priority="default"/>
      <NetworkInterface name = 'eth1' />
      <NetworkInterface autodetermine="true"/>
      <!-- <NetworkInterface address="8.8.8.8"/> a comment is no interface -->
    </Interfaces><NetworkInterfaceAddress> ::1 </NetworkInterfaceAddress></General>
    <Discovery><Peers><Peer address="10.0.0.9:7410"/><Peer address="[fe80::2]:7400"/>
      <Peer address="robot.local"/><Peer address="::1"/></Peers></Discovery></Domain></CycloneDDS>)");
  EXPECT_EQ(a.interface_addresses, (std::vector<std::string>{"192.168.3.4", "::1"}));
  EXPECT_EQ(a.interface_names, (std::vector<std::string>{"eth1"}));
  EXPECT_EQ(a.peers, (std::vector<std::string>{"10.0.0.9", "fe80::2", "::1"}));
}

TEST(AddressCheck, DdsInterfacesAndPeersOutsideTheListAreRefused) {
  const IpAllowList l = list(kDefault);
  DaemonConfig c;
  c.dds.config_uri = R"(<CycloneDDS><Domain><General><Interfaces>
      <NetworkInterface address="::1"/></Interfaces></General></Domain></CycloneDDS>)";
  EXPECT_EQ(check_allowed_addresses(c, l, no_interfaces), "");  // IPv6 loopback
  c.dds.config_uri = R"(<CycloneDDS><Domain><Discovery><Peers><Peer address="198.51.100.7"/>
      </Peers></Discovery></Domain></CycloneDDS>)";
  std::string why = check_allowed_addresses(c, l, no_interfaces);
  EXPECT_NE(why.find("dds.config_uri: Peer \"198.51.100.7\""), std::string::npos) << why;

  // An interface by name: refused when none of its addresses is allowed.
  const auto host = [](const std::string& name) {
    return name == "wan0" ? std::vector<std::string>{"203.0.113.1", "2001:db8::1"}
           : name == "lo" ? std::vector<std::string>{"127.0.0.1", "::1"}
                          : std::vector<std::string>{};
  };
  const std::string file = testing::TempDir() + "/address_check_cyclone.xml";
  std::ofstream(file) << R"(<CycloneDDS><Domain><General><Interfaces>
      <NetworkInterface name="wan0"/></Interfaces></General></Domain></CycloneDDS>)";
  c.dds.config_uri = "file://" + file;
  why = check_allowed_addresses(c, l, host);
  EXPECT_NE(why.find("NetworkInterface \"wan0\""), std::string::npos) << why;
  std::ofstream(file) << R"(<CycloneDDS><Domain><General><Interfaces>
      <NetworkInterface name="lo"/></Interfaces></General></Domain></CycloneDDS>)";
  EXPECT_EQ(check_allowed_addresses(c, l, host), "");
  // The shipped configurations pass with the default list (the host's real interfaces).
  for (const char* xml : {"cyclonedds.xml", "cyclonedds-loopback.xml"}) {
    c.dds.config_uri = std::string("file://") + RANGEFIT_SOURCE_DIR + "/systemd/" + xml;
    EXPECT_EQ(check_allowed_addresses(c, l), "") << xml;
  }
}

}  // namespace address_check_test
}  // namespace rangefit::daemon
