// write_object_model: what it writes reads back as the same model (sizes, shapes, tapers and
// links bit for bit), the comment lines are skipped by the reader, and a model that would not
// read back is refused before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "io/io_error.hpp"
#include "io/object_model_file.hpp"
#include "test/io/temp_dir.hpp"

namespace rangefit::io {
namespace object_model_write_test {

ObjectModel learnt_mallet() {
  ObjectModel m;
  m.name = "learnt mallet";
  m.parts.push_back({"part0", Superquadric{30.1234567891, 29.87654321, 56.5, 0.1, 0.987654321,
                                           -0.123456789, 0.333333333333}});
  m.parts.push_back({"part1", Superquadric{12.0, 10.0, 120.0, 0.1000000001, 1.0, 0.0, 0.0}});
  m.links.push_back({0, 1, std::numbers::pi / 2.0 - 0.0123, 169.87654321,
                     std::array<double, 2>{1.5, 0.0123456789}});
  return m;
}

TEST(ObjectModelWrite, WrittenFileReadsBackAsTheSameModel) {
  test::TempDir dir;
  const ObjectModel m = learnt_mallet();
  const auto file = dir.path("learnt.toml");
  write_object_model(file, m, "learnt by rangefit learn\nresidual 0.05 mm, visible 0.48");
  const ObjectModel back = read_object_model(file);
  EXPECT_EQ(back.name, m.name);
  ASSERT_EQ(back.parts.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const Superquadric &a = m.parts[i].shape, &b = back.parts[i].shape;
    EXPECT_EQ(back.parts[i].name, m.parts[i].name);
    EXPECT_EQ(a.a1, b.a1);
    EXPECT_EQ(a.a2, b.a2);
    EXPECT_EQ(a.a3, b.a3);
    EXPECT_EQ(a.eps1, b.eps1);
    EXPECT_EQ(a.eps2, b.eps2);
    EXPECT_EQ(a.kx, b.kx);
    EXPECT_EQ(a.ky, b.ky);
  }
  ASSERT_EQ(back.links.size(), 1u);
  EXPECT_EQ(back.links[0].first, 0u);
  EXPECT_EQ(back.links[0].second, 1u);
  EXPECT_NEAR(back.links[0].angle_rad, m.links[0].angle_rad, 1e-14);
  EXPECT_EQ(back.links[0].distance_mm, m.links[0].distance_mm);
  ASSERT_TRUE(back.links[0].bearing_rad.has_value());
  EXPECT_NEAR((*back.links[0].bearing_rad)[0], 1.5, 1e-14);
  EXPECT_NEAR((*back.links[0].bearing_rad)[1], 0.0123456789, 1e-14);
  // The comment is there for a person, as TOML comments.
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str().rfind("# learnt by rangefit learn\n# residual 0.05 mm, visible 0.48\n", 0),
            0u)
      << text.str();
  EXPECT_FALSE(std::filesystem::exists(dir.path("learnt.toml.tmp")));
}

TEST(ObjectModelWrite, ReplacesAnExistingFile) {
  test::TempDir dir;
  const auto file = dir.write("m.toml", "garbage that is not TOML [[[");
  write_object_model(file, learnt_mallet());
  EXPECT_EQ(read_object_model(file).parts.size(), 2u);
}

TEST(ObjectModelWrite, RefusesModelsThatWouldNotReadBack) {
  test::TempDir dir;
  const auto file = dir.path("bad.toml");
  ObjectModel empty;
  empty.name = "empty";
  EXPECT_THROW(write_object_model(file, empty), IoError);
  ObjectModel quoted = learnt_mallet();
  quoted.name = "a \"quoted\" name";
  EXPECT_THROW(write_object_model(file, quoted), IoError);
  ObjectModel invalid = learnt_mallet();
  invalid.parts[0].shape.eps1 = 0.01;
  EXPECT_THROW(write_object_model(file, invalid), IoError);
  ObjectModel dangling = learnt_mallet();
  dangling.links[0].second = 7;
  EXPECT_THROW(write_object_model(file, dangling), IoError);
  EXPECT_FALSE(std::filesystem::exists(file));
  ObjectModel past_right_angle = learnt_mallet();
  past_right_angle.links[0].bearing_rad = std::array<double, 2>{2.0, 0.0};
  EXPECT_THROW(write_object_model(file, past_right_angle), IoError);
  EXPECT_FALSE(std::filesystem::exists(file));
  EXPECT_THROW(write_object_model(dir.path("no/such/dir/m.toml"), learnt_mallet()), IoError);
}

}  // namespace object_model_write_test
}  // namespace rangefit::io
