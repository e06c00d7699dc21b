// Ids and names from requests are data: validated before they are queued or echoed, and escaped
// whenever they are logged.
#include <gtest/gtest.h>

#include <string>

#include "daemon/service/log_escape.hpp"
#include "daemon/service/request_validation.hpp"

namespace rangefit::daemon {
namespace hostile_strings_test {

TEST(LogEscape, ControlCharactersAndAnsiBecomeVisibleEscapes) {
  EXPECT_EQ(log_escape("scan-17"), "scan-17");
  EXPECT_EQ(log_escape("x\n[critical] FAKE LINE"), "x\\n[critical] FAKE LINE");
  EXPECT_EQ(log_escape("\x1b[31mred\x1b[0m"), "\\x1b[31mred\\x1b[0m");
  EXPECT_EQ(log_escape(std::string("a\0b\r\t\x7f\\", 7)), "a\\x00b\\r\\t\\x7f\\\\");
  EXPECT_EQ(log_escape("\xc2\x9b"
                       "2J"),
            "\\xc2\\x9b2J");  // C1 CSI, and any non-ASCII byte
  for (char c : log_escape(std::string(300, '\x01'))) {
    EXPECT_GE(static_cast<unsigned char>(c), 0x20);
    EXPECT_LT(static_cast<unsigned char>(c), 0x7f);
  }
}

TEST(LogEscape, LongTextIsCutWithItsLength) {
  const std::string id(8 << 20, 'A');  // an 8 MB id used to become an 8 MB log line
  const std::string logged = log_escape(id);
  EXPECT_EQ(logged, std::string(256, 'A') + "...(+8388352 bytes)");
  EXPECT_EQ(log_escape("abcdef", 3), "abc...(+3 bytes)");
}

TEST(CheckName, AcceptsPrintableAsciiWithinTheLength) {
  EXPECT_EQ(check_name("cell-3 scan #17", "request_id", 256), "");
  EXPECT_EQ(check_name("", "request_id", 256), "request_id is empty");
  EXPECT_EQ(check_name(std::string(257, 'a'), "request_id", 256),
            "request_id longer than 256 characters (257)");
  EXPECT_EQ(check_name("x\n[critical] FAKE LINE", "request_id", 256),
            "request_id has a non-printable character at 1 (only printable ASCII)");
  EXPECT_EQ(check_name("\x1b[31m", "model", 128),
            "model has a non-printable character at 0 (only printable ASCII)");
  EXPECT_NE(check_name("caf\xc3\xa9", "sensor", 128), "");
}

TEST(ValidateRequest, HostileIdsAndNamesAreRejectedWithoutEchoingThem) {
  const auto parsed = parse_config(
      "[[objects]]\nname = \"mallet\"\nscale_mm = [1, 1, 1]\n"
      "[[devices]]\nname = \"cam\"\nkind = \"stripe\"\nscene = \"s.toml\"\n",
      "t.toml");
  ASSERT_TRUE(parsed.config) << parsed.error;
  const DaemonConfig& config = *parsed.config;
  ScanRequest ok;
  ok.id = "a";
  ok.kind = DetectKind::kObject;
  ok.model = "mallet";
  ok.sensor = "cam";
  {
    ScanRequest r = ok;
    EXPECT_EQ(validate_request(r, config), "");
  }
  {
    ScanRequest r = ok;
    r.id = "a\n[critical] FAKE LINE\x1b[2J";
    EXPECT_EQ(validate_request(r, config),
              "request_id has a non-printable character at 1 (only printable ASCII)");
  }
  {
    ScanRequest r = ok;
    r.model = std::string(1 << 20, 'm');  // was echoed whole in the result
    const std::string why = validate_request(r, config);
    EXPECT_EQ(why, "model longer than 128 characters (1048576)");
  }
  {
    ScanRequest r = ok;
    r.sensor = "css\x1b]0;owned\x07";
    EXPECT_EQ(validate_request(r, config),
              "sensor has a non-printable character at 3 (only printable ASCII)");
  }
}

}  // namespace hostile_strings_test
}  // namespace rangefit::daemon
