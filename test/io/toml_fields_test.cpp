#include "io/toml_fields.hpp"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <string>

namespace rangefit::io {
namespace toml_fields_test {

std::string fields_error(const std::function<void()>& read) {
  try {
    read();
  } catch (const TomlError& e) {
    return e.what();
  }
  return "no TomlError";
}

TEST(TomlFields, EveryErrorNamesFileLineAndDottedField) {
  const toml::table root =
      parse_toml("[a]\nx = 1\n[a.b]\ny = \"text\"\nz = [1, 2]\nu = 0\n", "f.toml");
  TomlFields top(&root, "f.toml");
  TomlFields a = top.sub("a");
  double x = 0.0;
  a.read("x", x, 0.0, 10.0);
  EXPECT_EQ(x, 1.0);
  EXPECT_EQ(fields_error([&] { a.read("x", x, 2.0, 10.0); }),
            "f.toml:2: a.x: must be in [2, 10], got 1");
  TomlFields b = a.sub("b");
  EXPECT_EQ(fields_error([&] { b.read("y", x, 0.0, 1.0); }), "f.toml:4: a.b.y: must be a number");
  std::array<double, 3> v{};
  EXPECT_EQ(fields_error([&] { b.read("z", v, 0.0, 9.0); }),
            "f.toml:5: a.b.z: must be an array of 3 numbers");
  // A missing field fails at its table's line; a key nobody read is refused.
  EXPECT_EQ(fields_error([&] { b.require("w"); }), "f.toml:3: a.b.w: is required");
  std::string y;
  b.read("y", y);
  EXPECT_EQ(fields_error([&] { b.reject_unknown(); }), "f.toml:6: a.b.u: unknown field");
  EXPECT_EQ(fields_error([&] { top.only({"q"}); }), "f.toml:1: a: unknown field");
}

TEST(TomlFields, AnAbsentTableKeepsEveryDefault) {
  const toml::table root = parse_toml("n = 3\n[[item]]\nk = 1\n[[item]]\nk = 70000\n", "g.toml");
  TomlFields top(&root, "g.toml");
  TomlFields none = top.sub("missing");
  double d = 4.5;
  none.read("d", d, 0.0, 1.0);  // absent: not range-checked, unchanged
  EXPECT_EQ(d, 4.5);
  none.reject_unknown();
  const toml::array* items = top.table_array("item");
  ASSERT_NE(items, nullptr);
  TomlFields second = top.element("item", *items, 1);
  int k = 0;
  EXPECT_EQ(fields_error([&] { second.read_int("k", k, 0, 65535); }),
            "g.toml:5: item[1].k: must be in [0, 65535], got 70000");
  EXPECT_EQ(fields_error([&] { top.table_array("n"); }),
            "g.toml:1: n: must be an array of tables ([[n]])");
}

}  // namespace toml_fields_test
}  // namespace rangefit::io
