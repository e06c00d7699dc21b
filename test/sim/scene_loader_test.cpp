// Scene files from a hostile or careless hand: every problem is a SceneError naming the file, the
// line and the field, never a crash, an undefined conversion or a generation that runs for minutes.
#include "sim/scene_loader.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rangefit::sim {
namespace scene_loader_test {

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "s.toml", ".");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

std::string plate(const std::string& plate_fields, const std::string& bore_fields = "") {
  return "[[object]]\nname = \"p\"\ntype = \"bore_plate\"\n" + plate_fields +
         "\n[[object.bore]]\nname = \"b\"\nkind = \"notched\"\ndiameter = 12.0\n" + bore_fields +
         "\n";
}

TEST(SceneLoader, ABorePlateWithinTheLimitsLoads) {
  const Scene s = parse_scene(plate("segments = 64", "notches = 8"), "s.toml", ".");
  ASSERT_EQ(s.objects.size(), 1u);
  ASSERT_EQ(s.bores.size(), 1u);
}

TEST(SceneLoader, CountsAreWholeNumbersInRangeBeforeAnyConversion) {
  // 1e30 and 1e12 were undefined float-to-int casts; 800000 segments took 33 s and 0.9 GB.
  EXPECT_EQ(error_of(plate("segments = 1e30")),
            "s.toml:4: object[0].segments: must be a whole number in [8, 4096]");
  EXPECT_NE(error_of(plate("segments = 800000")).find("[8, 4096]"), std::string::npos);
  EXPECT_NE(error_of(plate("segments = 64.5")).find("whole number"), std::string::npos);
  EXPECT_EQ(error_of(plate("", "notches = 1e12")),
            "s.toml:9: object[0].bore[0].notches: must be a whole number in [1, 360]");
  EXPECT_NE(error_of(plate("", "notches = -3")).find("[1, 360]"), std::string::npos);
}

TEST(SceneLoader, TooManyEntriesAreRefused) {
  std::string text = "[[object]]\nname = \"p\"\ntype = \"sphere\"\nradius = 1\n";
  std::string many;
  for (int i = 0; i < 1001; ++i) many += text;
  EXPECT_NE(error_of(many).find("object: has more than 1000 entries"), std::string::npos);
}

TEST(SceneLoader, UnknownFieldsAreErrorsNamingTheLine) {
  EXPECT_EQ(error_of("[[object]]\nname = \"s\"\ntype = \"sphere\"\nradius = 1\nradios = 2\n"),
            "s.toml:5: object[0].radios: unknown field for type 'sphere'");
  EXPECT_EQ(error_of(plate("", "notch = 4")), "s.toml:9: object[0].bore[0].notch: unknown field");
  EXPECT_NE(error_of("[[object]]\nname = \"s\"\ntype = \"sphere\"\nradius = 1\n"
                     "[sensors.css]\npositon = [0, 0, 0]\n")
                .find("s.toml:6: sensors.css.positon: unknown field"),
            std::string::npos);
  EXPECT_NE(error_of("objects = 1\n").find("objects: unknown field"), std::string::npos);
}

TEST(SceneLoader, CrashInputsAndSpecialFilesAreErrors) {
  std::string key = "a";
  for (int i = 1; i < 40000; ++i) key += ".a";
  EXPECT_EQ(error_of(key + " = 1\n"), "s.toml:1: more than 32 dotted key segments");
  try {
    load_scene("/dev/zero");
    ADD_FAILURE() << "/dev/zero loaded as a scene";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

}  // namespace scene_loader_test
}  // namespace rangefit::sim
