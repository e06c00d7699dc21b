// DDS Security ([dds.security]): rangefitd's configuration becomes Cyclone's Domain/Security
// element, and on the wire only authenticated, permitted participants talk to the daemon. The
// end-to-end case makes a CA, identities and signed governance/permissions with
// scripts/make_dds_security.sh (openssl), runs rangefitd secured in its own process and checks
// that a secured participant exchanges a request and its result with it while an unsecured
// `rangefit watch` beside a secured one receives nothing.
#include "daemon/dds/dds_security.hpp"

#include <dds/dds.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "daemon/dds/client.hpp"
#include "test/daemon/daemon_process.hpp"
#include "test/daemon/replay_service.hpp"

namespace rangefit::daemon {
namespace dds_security_test {
namespace fs = std::filesystem;

DdsSecurityConfig security_in(const fs::path& dir, const std::string& identity) {
  DdsSecurityConfig s;
  s.identity_ca = dir / "ca_cert.pem";
  s.identity_certificate = dir / (identity + "_cert.pem");
  s.private_key = dir / (identity + "_key.pem");
  s.permissions_ca = dir / "ca_cert.pem";
  s.governance = dir / "governance.p7s";
  s.permissions = dir / "permissions.p7s";
  return s;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(DdsSecurityConfig, TableIsReadWithPathsRelativeToTheConfigFile) {
  const auto r = parse_config(
      "[dds.security]\nidentity_ca = \"pki/ca.pem\"\nidentity_certificate = \"pki/d.pem\"\n"
      "private_key = \"/abs/d_key.pem\"\npermissions_ca = \"pki/ca.pem\"\n"
      "governance = \"pki/gov.p7s\"\npermissions = \"pki/perm.p7s\"\n",
      "t.toml", "/etc/rangefitd");
  ASSERT_TRUE(r.config) << r.error;
  const DdsSecurityConfig& s = r.config->dds.security;
  EXPECT_TRUE(s.enabled());
  EXPECT_EQ(s.identity_ca, "/etc/rangefitd/pki/ca.pem");
  EXPECT_EQ(s.private_key, "/abs/d_key.pem");
  EXPECT_EQ(s.permissions, "/etc/rangefitd/pki/perm.p7s");
  EXPECT_EQ(s.plugin_dir, "/usr/lib/x86_64-linux-gnu/libddsc0debian");
  EXPECT_FALSE(parse_config("").config->dds.security.enabled()) << "off without the table";
}

TEST(DdsSecurityConfig, IncompleteOrMistypedTableNamesTheField) {
  const auto missing = parse_config("[dds.security]\nidentity_ca = \"ca.pem\"\n", "t.toml");
  EXPECT_NE(missing.error.find("dds.security.identity_certificate: is required"), std::string::npos)
      << missing.error;
  const auto typo = parse_config(
      "[dds.security]\nidentity_ca = \"a\"\nidentity_certificate = \"b\"\nprivate_key = \"c\"\n"
      "permissions_ca = \"d\"\ngovernance = \"e\"\npermissions = \"f\"\npassword = \"g\"\n",
      "t.toml");
  EXPECT_NE(typo.error.find("t.toml:8: dds.security.password: unknown field"), std::string::npos)
      << typo.error;
  const auto comma = parse_config("[dds.security]\nidentity_ca = \"a,b.pem\"\n", "t.toml");
  EXPECT_NE(comma.error.find("dds.security.identity_ca: must not contain ','"), std::string::npos)
      << comma.error;
}

TEST(DdsSecurityXml, NamesEveryDocumentAndThePluginsByAbsolutePath) {
  DdsSecurityConfig s = security_in("/pki", "rangefitd");
  s.governance = "/pki/a&b.p7s";
  const std::string xml = dds_security_xml(s);
  for (const char* part :
       {"<IdentityCA>file:/pki/ca_cert.pem</IdentityCA>",
        "<IdentityCertificate>file:/pki/rangefitd_cert.pem</IdentityCertificate>",
        "<PrivateKey>file:/pki/rangefitd_key.pem</PrivateKey>",
        "<PermissionsCA>file:/pki/ca_cert.pem</PermissionsCA>",
        "<Governance>file:/pki/a&amp;b.p7s</Governance>",
        "<Permissions>file:/pki/permissions.p7s</Permissions>",
        "path=\"/usr/lib/x86_64-linux-gnu/libddsc0debian/libdds_security_auth.so\"",
        "initFunction=\"init_access_control\"", "libdds_security_crypto.so"}) {
    EXPECT_NE(xml.find(part), std::string::npos) << part << "\n" << xml;
  }
}

TEST(DdsSecurityXml, OffLeavesTheConfigurationAlone) {
  EXPECT_EQ(dds_security_xml(DdsSecurityConfig{}), "");
  EXPECT_EQ(with_dds_security("file:///etc/c.xml", DdsSecurityConfig{}), "file:///etc/c.xml");
}

TEST(DdsSecurityXml, UnreadableDocumentIsAStartUpErrorNamingTheField) {
  try {
    with_dds_security("", security_in("/nonexistent", "rangefitd"));
    FAIL() << "accepted missing documents";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("dds.security.identity_ca: cannot read /nonexistent"),
              std::string::npos)
        << e.what();
  }
}

#if defined(RANGEFITD_PATH) && defined(RANGEFIT_CLI_PATH)
TEST(DdsSecurityEndToEnd, SecuredParticipantsExchangeMessagesAndAnUnsecuredOneReceivesNothing) {
  if (std::system("command -v openssl >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "openssl is missing: cannot make the test CA and signed documents";
  }
  if (!fs::exists(DdsSecurityConfig{}.plugin_dir / "libdds_security_auth.so")) {
    GTEST_SKIP() << "Cyclone's security plugins are missing (Debian: libddsc0debian)";
  }
  const fs::path dir = test::fresh_test_dir("rangefit_dds_security_test");
  const fs::path pki = dir / "pki";
  ASSERT_EQ(std::system(("bash " RANGEFIT_SOURCE_DIR "/scripts/make_dds_security.sh " +
                         pki.string() + " rangefitd client >/dev/null")
                            .c_str()),
            0);
  // A domain of its own, above the 1..200 of test::dds_test_domain() that the other DDS tests
  // (and their daemons, which an unsecured watcher would hear) use; governance covers 0..230.
  const std::uint32_t domain = 201 + test::dds_test_domain() % 30;
  const std::string loopback = std::getenv("CYCLONEDDS_URI");  // set by dds_test_domain()
  {
    std::ofstream toml(dir / "rangefitd.toml");
    toml << "[service]\nbore_sensor = \"css\"\n[dds]\ndomain_id = " << domain
         << "\ndiagnostics_period_s = 0.2\n[dds.security]\nidentity_ca = \"pki/ca_cert.pem\"\n"
         << "identity_certificate = \"pki/rangefitd_cert.pem\"\n"
         << "private_key = \"pki/rangefitd_key.pem\"\npermissions_ca = \"pki/ca_cert.pem\"\n"
         << "governance = \"pki/governance.p7s\"\npermissions = \"pki/permissions.p7s\"\n"
         << "[spool]\ndirectory = \"" << (dir / "spool").string() << "\"\n"
         << "[[devices]]\nname = \"css\"\nkind = \"css\"\ndriver = \"replay\"\n"
         << "replay_file = \"" << (dir / "none.ply").string() << "\"\n";
  }
  test::DaemonProcess daemon(RANGEFITD_PATH, dir / "rangefitd.toml");
  ASSERT_TRUE(daemon.started());

  // Secured participant in this process: the client identity on a domain created with it.
  const dds_entity_t secured_domain =
      dds_create_domain(domain, with_dds_security(loopback, security_in(pki, "client")).c_str());
  ASSERT_GT(secured_domain, 0) << dds_strretcode(secured_domain);
  {
    DdsClient client(domain);
    ASSERT_TRUE(client.wait_for_daemon(std::chrono::seconds(30)));
    ScanRequest request;
    request.id = "secured-1";
    request.kind = DetectKind::kBore;
    request.bore.radius_mm = 5;
    ASSERT_TRUE(client.send(request, false));
    const auto result = client.wait_result("secured-1", std::chrono::seconds(30));
    ASSERT_TRUE(result) << "no result over the secured domain";
    EXPECT_NE(result->reason.find("scan failed"), std::string::npos) << result->reason;

    // Beside it, `rangefit watch` twice for the same 4 s: once with the client identity, once
    // without security. Only the first hears the daemon (state, diagnostics).
    const std::string secured_uri = with_dds_security(loopback, security_in(pki, "client"));
    const std::string watch = std::string(RANGEFIT_CLI_PATH) + " watch --domain " +
                              std::to_string(domain) + " --seconds 4";
    const std::string cmd = "(CYCLONEDDS_URI='" + secured_uri + "' " + watch + " > " +
                            (dir / "secured.out").string() + " 2>&1 & CYCLONEDDS_URI='" + loopback +
                            "' " + watch + " > " + (dir / "plain.out").string() + " 2>" +
                            (dir / "plain.err").string() + " & wait)";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
  }
  dds_delete(secured_domain);
  EXPECT_NE(read_file(dir / "secured.out").find("\"state\""), std::string::npos)
      << read_file(dir / "secured.out");
  // stdout carries what arrived; Cyclone's own warnings, if any, go to plain.err.
  EXPECT_EQ(read_file(dir / "plain.out"), "") << "the unsecured participant received data";
  EXPECT_EQ(daemon.stop(), 0);
  fs::remove_all(dir);
}
#endif

}  // namespace dds_security_test
}  // namespace rangefit::daemon
