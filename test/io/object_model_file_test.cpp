#include "io/object_model_file.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "io/io_error.hpp"

namespace rangefit::io {
namespace object_model_file_test {

std::string model_error(const std::string& text) {
  try {
    parse_object_model(text, "model.toml");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(ObjectModelFile, ReadsTheShippedMalletWithItsLink) {
  const ObjectModel m =
      read_object_model(std::string(RANGEFIT_SOURCE_DIR) + "/data/models/mallet.toml");
  EXPECT_EQ(m.name, "mallet");
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_EQ(m.parts[1].name, "shaft");
  EXPECT_DOUBLE_EQ(m.parts[1].shape.a3, 120.0);
  EXPECT_DOUBLE_EQ(m.parts[0].shape.eps1, 0.1);
  ASSERT_EQ(m.links.size(), 1u);
  EXPECT_EQ(m.links[0].first, 0u);
  EXPECT_EQ(m.links[0].second, 1u);
  EXPECT_NEAR(m.links[0].angle_rad, std::numbers::pi / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.links[0].distance_mm, 170.0);
  ASSERT_TRUE(m.links[0].bearing_rad.has_value());
  EXPECT_NEAR((*m.links[0].bearing_rad)[0], std::numbers::pi / 2.0, 1e-12);
  EXPECT_EQ((*m.links[0].bearing_rad)[1], 0.0);
}

// A link written before bearings existed reads as one without them; bearings past 90 deg (they
// are folded: a part's axis has no sign) or not two of them are refused with the field named.
TEST(ObjectModelFile, LinkBearingsAreOptionalAndChecked) {
  const std::string parts =
      "name = \"m\"\n[[part]]\nname = \"a\"\nsize = [1, 1, 1]\nshape = [1, 1]\n"
      "[[part]]\nname = \"b\"\nsize = [1, 1, 1]\nshape = [1, 1]\n"
      "[[link]]\nparts = [\"a\", \"b\"]\nangle_deg = 90\ndistance = 10\n";
  EXPECT_FALSE(parse_object_model(parts, "m.toml").links[0].bearing_rad.has_value());
  const ObjectModel with = parse_object_model(parts + "bearing_deg = [45, 0]\n", "m.toml");
  ASSERT_TRUE(with.links[0].bearing_rad.has_value());
  EXPECT_NEAR((*with.links[0].bearing_rad)[0], std::numbers::pi / 4.0, 1e-12);
  const ObjectModel back = parse_object_model(format_object_model(with), "m.toml");
  ASSERT_TRUE(back.links[0].bearing_rad.has_value());
  EXPECT_NEAR((*back.links[0].bearing_rad)[0], std::numbers::pi / 4.0, 1e-12);
  for (const char* bad : {"bearing_deg = [120, 0]\n", "bearing_deg = [45]\n",
                          "bearing_deg = [-1, 0]\n", "bearing_deg = \"x\"\n"}) {
    const std::string e = model_error(parts + bad);
    EXPECT_NE(e.find("bearing_deg"), std::string::npos) << bad << ": " << e;
  }
}

TEST(ObjectModelFile, ReadsAllShippedModelsAsValidParts) {
  for (const char* name : {"cylinder", "box", "sphere", "cone", "mallet"}) {
    const ObjectModel m =
        read_object_model(std::string(RANGEFIT_SOURCE_DIR) + "/data/models/" + name + ".toml");
    for (const ModelPart& p : m.parts) EXPECT_TRUE(p.shape.valid()) << name;
  }
}

TEST(ObjectModelFile, TaperDefaultsToZeroAndFormatRoundTrips) {
  const ObjectModel m = parse_object_model(
      "name = \"c\"\n[[part]]\nname = \"p\"\nsize = [1, 2, 3]\nshape = [0.5, 1]\n", "m.toml");
  EXPECT_EQ(m.parts[0].shape.kx, 0.0);
  const ObjectModel back = parse_object_model(format_object_model(m), "m.toml");
  EXPECT_EQ(back.parts[0].shape.a2, 2.0);
  EXPECT_EQ(back.parts[0].shape.eps1, 0.5);
}

TEST(ObjectModelFile, ErrorsNameTheLineAndTheField) {
  const std::string bad_size =
      "name = \"x\"\n[[part]]\nname = \"p\"\nsize = [1, 2]\nshape = [1, 1]\n";
  const std::string e1 = model_error(bad_size);
  EXPECT_EQ(e1.rfind("model.toml:4: ", 0), 0u) << e1;
  EXPECT_NE(e1.find("part[0].size"), std::string::npos) << e1;

  const std::string bad_shape =
      "name = \"x\"\n[[part]]\nname = \"p\"\nsize = [1, 2, 3]\nshape = [0.01, 1]\n";
  EXPECT_NE(model_error(bad_shape).find("part[0].shape"), std::string::npos);

  const std::string bad_link =
      "name = \"x\"\n[[part]]\nname = \"p\"\nsize = [1, 2, 3]\nshape = [1, 1]\n"
      "[[link]]\nparts = [\"p\", \"q\"]\nangle_deg = 90\ndistance = 10\n";
  const std::string e3 = model_error(bad_link);
  EXPECT_NE(e3.find("link[0].parts"), std::string::npos) << e3;
  EXPECT_EQ(e3.rfind("model.toml:7: ", 0), 0u) << e3;

  EXPECT_NE(model_error("name = \"x\"\n").find("part"), std::string::npos);
  EXPECT_NE(model_error("[[part]]\nname = \"p\"\n").find("name: is required"), std::string::npos);
  EXPECT_EQ(model_error("name = \"x\"\nsize = [1, 2\n").rfind("model.toml:2: ", 0), 0u);
}

TEST(ObjectModelFile, UnknownKeysAreErrorsNamingTheLine) {
  const std::string part = "[[part]]\nname = \"p\"\nsize = [1, 2, 3]\nshape = [1, 1]\n";
  EXPECT_EQ(model_error("name = \"x\"\nnmae = \"y\"\n" + part),
            "model.toml:2: nmae: unknown field");
  EXPECT_EQ(model_error("name = \"x\"\n" + part + "tapper = [0, 0]\n"),
            "model.toml:6: part[0].tapper: unknown field");
  EXPECT_EQ(model_error("name = \"x\"\n" + part + "[[link]]\nparts = [\"p\", \"p\"]\nangle = 9\n"),
            "model.toml:8: link[0].angle: unknown field");
}

TEST(ObjectModelFile, EmptyOrMissingFileIsAnError) {
  EXPECT_FALSE(model_error("").empty());
  EXPECT_THROW(read_object_model("/nonexistent/model.toml"), IoError);
}

}  // namespace object_model_file_test
}  // namespace rangefit::io
