#include "io/toml_fields.hpp"

#include <sstream>

namespace rangefit::io {
namespace {

std::string range(double lo, double hi) {
  std::ostringstream s;
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}

}  // namespace

std::string TomlFields::field(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

const toml::node* TomlFields::find(std::string_view key) {
  used_.insert(std::string(key));
  return table_ == nullptr ? nullptr : table_->get(key);
}

void TomlFields::fail(std::string_view key, std::string_view problem) const {
  const toml::node* n = table_ == nullptr ? nullptr : table_->get(key);
  const std::uint32_t line = n != nullptr        ? n->source().begin.line
                             : table_ != nullptr ? table_->source().begin.line
                                                 : 0;
  throw TomlError(source_, line, field(key) + ": " + std::string(problem));
}

void TomlFields::fail_table(std::string_view problem) const {
  const std::uint32_t line = table_ != nullptr ? table_->source().begin.line : 0;
  throw TomlError(source_, line,
                  (path_.empty() ? std::string() : path_ + ": ") + std::string(problem));
}

const toml::table* TomlFields::sub_table(std::string_view key) {
  const toml::node* n = find(key);
  if (n == nullptr) return nullptr;
  if (!n->is_table()) fail(key, "must be a table");
  return n->as_table();
}

TomlFields TomlFields::sub(std::string_view key) {
  const toml::node* n = find(key);
  if (n != nullptr && !n->is_table()) fail(key, "must be a table");
  return TomlFields(n == nullptr ? nullptr : n->as_table(), source_, field(key));
}

const toml::array* TomlFields::table_array(std::string_view key) {
  const toml::node* n = find(key);
  if (n == nullptr) return nullptr;
  if (!n->is_array_of_tables()) fail(key, "must be an array of tables ([[" + field(key) + "]])");
  return n->as_array();
}

TomlFields TomlFields::element(std::string_view key, const toml::array& array,
                               std::size_t i) const {
  return TomlFields(array[i].as_table(), source_, field(key) + "[" + std::to_string(i) + "]");
}

void TomlFields::read(std::string_view key, std::string& out) {
  if (const toml::node* n = find(key)) {
    if (!n->is_string()) fail(key, "must be a string");
    out = n->as_string()->get();
  }
}

void TomlFields::read(std::string_view key, bool& out) {
  if (const toml::node* n = find(key)) {
    if (!n->is_boolean()) fail(key, "must be true or false");
    out = n->as_boolean()->get();
  }
}

void TomlFields::read(std::string_view key, double& out, double lo, double hi) {
  if (const toml::node* n = find(key)) {
    double v = 0.0;
    if (n->is_integer()) {
      v = static_cast<double>(n->as_integer()->get());
    } else if (n->is_floating_point()) {
      v = n->as_floating_point()->get();
    } else {
      fail(key, "must be a number");
    }
    if (!std::isfinite(v) || v < lo || v > hi) {
      std::ostringstream s;
      s << "must be in " << range(lo, hi) << ", got " << v;
      fail(key, s.str());
    }
    out = v;
  }
}

void TomlFields::read(std::string_view key, std::int64_t& out, std::int64_t lo, std::int64_t hi) {
  if (const toml::node* n = find(key)) {
    if (!n->is_integer()) fail(key, "must be an integer");
    const std::int64_t v = n->as_integer()->get();
    if (v < lo || v > hi) {
      fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                    std::to_string(v));
    }
    out = v;
  }
}

void TomlFields::read_numbers(std::string_view key, double* out, std::size_t count, double lo,
                              double hi) {
  const toml::node* n = find(key);
  if (n == nullptr) return;
  const toml::array* a = n->as_array();
  if (a == nullptr || a->size() != count)
    fail(key, "must be an array of " + std::to_string(count) + " numbers");
  for (std::size_t i = 0; i < count; ++i) {
    const toml::node& e = (*a)[i];
    const std::optional<double> v =
        e.is_integer() || e.is_floating_point() ? e.value<double>() : std::nullopt;
    if (!v || !std::isfinite(*v) || *v < lo || *v > hi)
      fail(key, "element " + std::to_string(i) + " must be a number in " + range(lo, hi));
    out[i] = *v;
  }
}

void TomlFields::require(std::string_view key, std::string_view hint) const {
  if (!has(key)) {
    fail(key, hint.empty() ? std::string("is required") : "is required " + std::string(hint));
  }
}

void TomlFields::reject_unknown() const {
  if (table_ == nullptr) return;
  for (const auto& [k, v] : *table_) {
    if (!used_.contains(k.str())) fail(k.str(), "unknown field");
  }
}

}  // namespace rangefit::io

namespace rangefit::io {

void TomlFields::only(std::initializer_list<std::string_view> known) const {
  if (table_ == nullptr) return;
  for (const auto& [k, v] : *table_) {
    bool found = false;
    for (std::string_view name : known) found = found || k.str() == name;
    if (!found) fail(k.str(), "unknown field");
  }
}

}  // namespace rangefit::io
