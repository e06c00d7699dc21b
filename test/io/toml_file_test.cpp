#include "io/toml_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>

#include "io/object_model_file.hpp"
#include "temp_dir.hpp"

namespace rangefit::io {
namespace toml_file_test {

std::string toml_error(std::string_view text) {
  try {
    parse_toml(text, "f.toml");
  } catch (const TomlError& e) {
    return e.what();
  }
  return "";
}

std::string dotted_key(std::size_t segments) {
  std::string key = "a";
  for (std::size_t i = 1; i < segments; ++i) key += ".a";
  return key;
}

TEST(TomlFile, ParsesOrdinaryTomlIncludingDotsInStringsNumbersAndComments) {
  const toml::table t = parse_toml(R"(
name = "a.b.c.d.e.f.g.h.i.j.k.l.m.n.o.p.q.r.s.t.u.v.w.x.y.z.a.b.c.d.e.f.g.h" # x.x.x.x
v = [1.5, 2.5e+3, -0.25]
lit = 'C:\dir\[x]{'
multi = """
  "[[[{{{"" """
when = 1979-05-27T07:32:00.999
[server."10.0.0.5".port]
nested = [[1, [2, [3]]], { a.b = 1 }]
)",
                                   "f.toml");
  EXPECT_EQ(t["name"].value<std::string>()->size(), 67u);
  EXPECT_EQ(t["server"]["10.0.0.5"]["port"]["nested"][1]["a"]["b"].value<int>(), 1);
  EXPECT_EQ(t["multi"].value<std::string>(), "  \"[[[{{{\"\" ");
}

TEST(TomlFile, RefusesAKeyOfFortyThousandSegmentsBeforeTomlPlusPlusOverflowsTheStack) {
  const std::string key = dotted_key(40000);
  EXPECT_EQ(toml_error(key + " = 1\n"), "f.toml:1: more than 32 dotted key segments");
  EXPECT_EQ(toml_error("x = 1\n[" + key + "]\n"), "f.toml:2: more than 32 dotted key segments");
  EXPECT_EQ(toml_error("x = { " + key + " = 1 }\n"), "f.toml:1: more than 32 dotted key segments");
  // Quoted segments count too, and a string that ends with extra quotes hides nothing.
  EXPECT_NE(toml_error("\"a\"." + key + " = 1\n").find("dotted key segments"), std::string::npos);
  EXPECT_NE(toml_error("x = { a = \"\"\"q\"\"\"\", " + key + " = 1 }\n").find("dotted key"),
            std::string::npos);
  EXPECT_EQ(toml_error(dotted_key(32) + " = 1\n"), "");
}

TEST(TomlFile, RefusesDeepNesting) {
  EXPECT_EQ(toml_error("x = " + std::string(100000, '[') + "\n"),
            "f.toml:1: nested deeper than 32 brackets or braces");
  EXPECT_NE(toml_error("x = " + std::string(5000, '{')).find("nested deeper"), std::string::npos);
  EXPECT_EQ(toml_error("x = " + std::string(30, '[') + std::string(30, ']') + "\n"), "");
}

TEST(TomlFile, RefusesInvalidUtf8AndNonAsciiOutsideStrings) {
  // c7 b6 20 as a whole file reached TOML_UNREACHABLE inside toml++ 3.3.
  EXPECT_EQ(toml_error("\xc7\xb6 "), "f.toml:1: non-ASCII character outside a string or comment");
  EXPECT_EQ(toml_error("x = 1\n\xff\n"), "f.toml:2: not valid UTF-8 (byte 6)");
  EXPECT_NE(toml_error("x = \"\xed\xa0\x80\"").find("not valid UTF-8"), std::string::npos);
  EXPECT_NE(toml_error("x = \"\xc0\xaf\"").find("not valid UTF-8"), std::string::npos);
  EXPECT_EQ(toml_error("x = \"\xc7\xb6 \" # \xe2\x82\xac\n"), "");
}

TEST(TomlFile, RefusesNonAsciiWhereTomlPlusPlusTestsItForWhitespace) {
  // toml++ scans a bare value up to ~127 characters, quotes included, testing each for
  // whitespace: U+FEF5 there reached TOML_UNREACHABLE (found by test/fuzz/toml_fuzz).
  EXPECT_EQ(toml_error("x = ++fm'''\xef\xbb\xb5'''\n"),
            "f.toml:1: non-ASCII character outside a string or comment");
  EXPECT_EQ(toml_error("taper = [0.0, 0.'\xc7\xb6 0]\n"),
            "f.toml:1: non-ASCII character outside a string or comment");
  EXPECT_EQ(toml_error("taper = [\n  0.0,\n  0.'\xc7\xb6 0]\n"),
            "f.toml:3: non-ASCII character outside a string or comment");
  EXPECT_EQ(toml_error("x = 1X=\"cy\xef\xba\xbfr\"\n"),
            "f.toml:1: non-ASCII character outside a string or comment");
  EXPECT_EQ(toml_error("d = 1979-05-27 '\xc3\xa4'\n"),
            "f.toml:1: non-ASCII character outside a string or comment");
  EXPECT_EQ(toml_error("x = \"a\\\xc3\xa4\"\n"),
            "f.toml:1: non-ASCII character after a backslash in a string");
  EXPECT_EQ(toml_error("x = \"\"\"a\\  \n\n   \xc3\xa4\"\"\"\n"),
            "f.toml:3: non-ASCII character after a line-ending backslash in a string");
  EXPECT_EQ(toml_error("\"\"\"s\\\t\t\xcd\x8b\"\"\" = 1\n"),
            "f.toml:1: non-ASCII character after a line-ending backslash in a string");
  // A string right after '=' is a string: what follows it is outside (U+FEFE there reached
  // TOML_UNREACHABLE, found by test/fuzz/fusion_config_fuzz), its own text is inside.
  EXPECT_EQ(toml_error("x =\" == \"\xef\xbb\xbe\"\n"),
            "f.toml:1: non-ASCII character outside a string or comment");
  EXPECT_EQ(toml_error("x =\"\xc3\xa4\"\n"), "");
  // Everywhere else in strings and comments non-ASCII text is fine.
  EXPECT_EQ(toml_error("\"k\xc3\xa4\" = [\"\xc3\xa4\", '\xc3\xb6']  # \xc3\xbc\n"
                       "y = \"\"\"\n\xc3\xa4\\n\"\"\"\n[a.\"\xc3\xa4\"]\n"),
            "");
}

// TOML allows no control character but tab and line ends, not even in a comment: toml++ read
// on past a NUL in a bare value into the comment after it, where U+FD9B reached
// TOML_UNREACHABLE (found by test/fuzz/fusion_config_fuzz).
TEST(TomlFile, RefusesControlCharactersEverywhere) {
  EXPECT_EQ(toml_error(std::string("x =6----=---\0 9#\xef\xb6\x9b#", 20)),
            "f.toml:1: control character 0 (byte 12)");
  EXPECT_EQ(toml_error("x = 1\n# a\x01"
                       "b\n"),
            "f.toml:2: control character 1 (byte 9)");
  EXPECT_EQ(toml_error("x = \"a\x7f\"\n"), "f.toml:1: control character 127 (byte 6)");
  EXPECT_EQ(toml_error("x = 1\r\ny = \"\tz\"\t# tab\n"), "");
}

// toml++ reads a date, a space and a digit as a date-time and takes the character after the
// digit whatever it is (here a line end), then reads on: U+01F6 there reached TOML_UNREACHABLE
// (found by test/fuzz/object_model_fuzz). An ordinary date-time is fine.
TEST(TomlFile, RefusesNonAsciiWhereTomlPlusPlusReadsOnAfterADateAndASpace) {
  EXPECT_EQ(toml_error("2=30w0-05-05 0\n\"\xc7\xb6"),
            "f.toml:1: non-ASCII character right after a date and time separated by a space");
  // toml++ leaves the '_' digit separators out of the 10 characters it looks at.
  EXPECT_EQ(toml_error("2=30w0-0_____5-05 0\n\"\xc7\xb6"),
            "f.toml:1: non-ASCII character right after a date and time separated by a space");
  EXPECT_EQ(toml_error("2=30w__5-0_______5-0= 0\n\"s.hap\xc7\xb6"),
            "f.toml:1: non-ASCII character right after a date and time separated by a space");
  EXPECT_EQ(toml_error("d = 1979-05-27 07:32:00\nname = \"M\xc3\xbcller\"\n"), "");
}

TEST(TomlFile, ReportsTomlPlusPlusErrorsWithFileAndLine) {
  const std::string e = toml_error("x = 1\ny = \n");
  EXPECT_EQ(e.rfind("f.toml:2: ", 0), 0u) << e;
}

TEST(TomlFile, ReadsOnlyRegularFilesOfBoundedSize) {
  test::TempDir dir;
  auto error_reading = [](const std::filesystem::path& p, std::size_t cap = kMaxTomlBytes) {
    try {
      read_toml_file(p, cap);
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_reading("/dev/zero"),
            "/dev/zero: is not a regular file (a device, FIFO or socket)");
  EXPECT_EQ(error_reading(dir.path("")), dir.path("").string() + ": is a directory, not a file");
  const auto fifo = dir.path("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_reading(fifo).find("not a regular file"), std::string::npos);  // no hang
  const auto big = dir.write("big.toml", std::string(101, '#'));
  EXPECT_EQ(error_reading(big, 100), big.string() + ": is 101 bytes, more than the limit of 100");
  EXPECT_EQ(read_toml_file(dir.write("ok.toml", "x = 1\n")), "x = 1\n");
}

TEST(TomlFile, ObjectModelsGoThroughTheGuard) {
  test::TempDir dir;
  const auto crash = dir.write("crash.toml", dotted_key(40000) + " = 1\n");
  EXPECT_THROW(read_object_model(crash), IoError);
  EXPECT_THROW(read_object_model(dir.write("ub.toml", "\xc7\xb6 ")), IoError);
  EXPECT_THROW(read_object_model("/dev/zero"), IoError);
}

}  // namespace toml_file_test
}  // namespace rangefit::io
