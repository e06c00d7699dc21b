#pragma once
// The one TOML field reader of every rangefit loader (daemon config, [fusion], scenes, object
// models). A TomlFields reads one table that sits at a dotted path in a file: each read checks
// type and range, every failure is a TomlError "<file>:<line>: <path>.<key>: <problem>" (the
// line of the field, or of its table when the field is missing), and reject_unknown() refuses
// any key nobody read, so a typo never falls back to a default silently.
//
// A missing table is allowed: a TomlFields over nullptr reads nothing and keeps every default.

#include <toml++/toml.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>

#include "io/toml_file.hpp"

namespace rangefit::io {

class TomlFields {
 public:
  TomlFields(const toml::table* table, std::string source, std::string path = {})
      : table_(table), source_(std::move(source)), path_(std::move(path)) {}

  // The fields of the sub-table `key` (absent: an empty reader); "must be a table" otherwise.
  TomlFields sub(std::string_view key);
  // The sub-table `key` itself (marked as read): nullptr when absent, "must be a table" otherwise.
  const toml::table* sub_table(std::string_view key);
  // The [[key]] array of tables (nullptr when absent), and a reader for its element i.
  const toml::array* table_array(std::string_view key);
  TomlFields element(std::string_view key, const toml::array& array, std::size_t i) const;

  const std::string& source() const { return source_; }
  const toml::table* table() const { return table_; }
  std::string field(std::string_view key) const;  // "<path>.<key>"
  bool has(std::string_view key) const { return table_ != nullptr && table_->contains(key); }
  // The node, marked as read; nullptr when absent.
  const toml::node* find(std::string_view key);

  [[noreturn]] void fail(std::string_view key, std::string_view problem) const;
  // A problem of the table as a whole (a cross-field rule), at the table's line.
  [[noreturn]] void fail_table(std::string_view problem) const;

  // Each read leaves `out` unchanged when the key is absent.
  void read(std::string_view key, std::string& out);
  void read(std::string_view key, bool& out);
  void read(std::string_view key, double& out, double lo, double hi);  // integers convert
  void read(std::string_view key, std::int64_t& out, std::int64_t lo, std::int64_t hi);
  template <class Int>
  void read_int(std::string_view key, Int& out, std::int64_t lo, std::int64_t hi) {
    std::int64_t v = static_cast<std::int64_t>(out);
    read(key, v, lo, hi);
    out = static_cast<Int>(v);
  }
  template <std::size_t N>
  void read(std::string_view key, std::array<double, N>& out, double lo, double hi) {
    read_numbers(key, out.data(), N, lo, hi);
  }
  void read(std::string_view key, Eigen::Vector3d& out, double lo, double hi) {
    read_numbers(key, out.data(), 3, lo, hi);
  }
  // A key that must be present: fails with "is required" (plus `hint`) when absent.
  void require(std::string_view key, std::string_view hint = {}) const;

  // Call after reading: any key not read is a typo or a field this version does not know.
  void reject_unknown() const;
  // The same check up front, for tables whose other checks would otherwise speak first.
  void only(std::initializer_list<std::string_view> known) const;

 private:
  void read_numbers(std::string_view key, double* out, std::size_t n, double lo, double hi);

  const toml::table* table_;
  std::string source_;
  std::string path_;
  std::set<std::string, std::less<>> used_;
};

}  // namespace rangefit::io
