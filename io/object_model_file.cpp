#include "io/object_model_file.hpp"

#include <toml++/toml.h>
#include <cmath>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <system_error>

#include "io/io_error.hpp"
#include "io/toml_file.hpp"

namespace rangefit::io {
namespace {

constexpr std::size_t kMaxFileBytes = 1 << 20;  // model files are tiny; refuse anything huge
constexpr std::size_t kMaxParts = 16;

// "<file>:<line>: field '<field>': <problem>", the format of every TOML loader.
[[noreturn]] void fail(const std::filesystem::path& file, const toml::source_region& where,
                       const std::string& field, const std::string& problem) {
  throw TomlError(file.string(), where.begin.line, "field '" + field + "': " + problem);
}

// Keys this version reads; anything else is a typo that must not fall back to a default.
void reject_unknown(const std::filesystem::path& file, const toml::table& table,
                    const std::string& prefix, std::initializer_list<std::string_view> known) {
  for (const auto& [key, node] : table) {
    bool found = false;
    for (std::string_view k : known) found = found || key.str() == k;
    if (!found) fail(file, node.source(), prefix + std::string(key.str()), "unknown field");
  }
}

double number(const std::filesystem::path& file, const toml::node& node, const std::string& field) {
  const std::optional<double> v = node.value<double>();
  if (!v || !std::isfinite(*v)) fail(file, node.source(), field, "expected a finite number");
  return *v;
}

std::vector<double> numbers(const std::filesystem::path& file, const toml::node& node,
                            const std::string& field, std::size_t count) {
  const toml::array* arr = node.as_array();
  if (arr == nullptr || arr->size() != count) {
    fail(file, node.source(), field, "expected an array of " + std::to_string(count) + " numbers");
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < count; ++i) {
    out.push_back(number(file, *arr->get(i), field + "[" + std::to_string(i) + "]"));
  }
  return out;
}

const toml::node& required(const std::filesystem::path& file, const toml::table& table,
                           std::string_view key, const std::string& field) {
  const toml::node* node = table.get(key);
  if (node == nullptr) fail(file, table.source(), field, "missing");
  return *node;
}

std::string text(const std::filesystem::path& file, const toml::node& node,
                 const std::string& field) {
  const std::optional<std::string> v = node.value<std::string>();
  if (!v || v->empty()) fail(file, node.source(), field, "expected a non-empty string");
  return *v;
}

ModelPart parse_part(const std::filesystem::path& file, const toml::table& t, std::size_t i) {
  const std::string f = "part[" + std::to_string(i) + "]";
  reject_unknown(file, t, f + ".", {"name", "size", "shape", "taper"});
  ModelPart part;
  part.name = text(file, required(file, t, "name", f + ".name"), f + ".name");
  const toml::node& size_node = required(file, t, "size", f + ".size");
  const std::vector<double> size = numbers(file, size_node, f + ".size", 3);
  for (double a : size) {
    if (!(a > 0.0)) fail(file, size_node.source(), f + ".size", "sizes must be > 0 mm");
  }
  const toml::node& shape_node = required(file, t, "shape", f + ".shape");
  const std::vector<double> shape = numbers(file, shape_node, f + ".shape", 2);
  for (double e : shape) {
    if (e < 0.1 || e > 2.0)
      fail(file, shape_node.source(), f + ".shape", "eps must be in [0.1, 2]");
  }
  std::vector<double> taper = {0.0, 0.0};
  if (const toml::node* taper_node = t.get("taper")) {
    taper = numbers(file, *taper_node, f + ".taper", 2);
    for (double k : taper) {
      if (k < -1.0 || k > 1.0)
        fail(file, taper_node->source(), f + ".taper", "k must be in [-1, 1]");
    }
  }
  part.shape = Superquadric{size[0], size[1], size[2], shape[0], shape[1], taper[0], taper[1]};
  return part;
}

PartLink parse_link(const std::filesystem::path& file, const toml::table& t, std::size_t i,
                    const std::vector<ModelPart>& parts) {
  const std::string f = "link[" + std::to_string(i) + "]";
  reject_unknown(file, t, f + ".", {"parts", "angle_deg", "distance"});
  const toml::node& names_node = required(file, t, "parts", f + ".parts");
  const toml::array* names = names_node.as_array();
  if (names == nullptr || names->size() != 2) {
    fail(file, names_node.source(), f + ".parts", "expected two part names");
  }
  std::size_t idx[2] = {0, 0};
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string name = text(file, *names->get(k), f + ".parts");
    std::size_t j = 0;
    while (j < parts.size() && parts[j].name != name) ++j;
    if (j == parts.size())
      fail(file, names->get(k)->source(), f + ".parts", "no part named '" + name + "'");
    idx[k] = j;
  }
  if (idx[0] == idx[1])
    fail(file, names_node.source(), f + ".parts", "a part cannot link to itself");
  const toml::node& angle_node = required(file, t, "angle_deg", f + ".angle_deg");
  const double angle = number(file, angle_node, f + ".angle_deg");
  if (angle < 0.0 || angle > 180.0)
    fail(file, angle_node.source(), f + ".angle_deg", "must be in [0, 180]");
  const toml::node& dist_node = required(file, t, "distance", f + ".distance");
  const double distance = number(file, dist_node, f + ".distance");
  if (distance < 0.0) fail(file, dist_node.source(), f + ".distance", "must be >= 0 mm");
  return PartLink{idx[0], idx[1], angle * std::numbers::pi / 180.0, distance};
}

const toml::array* table_array(const std::filesystem::path& file, const toml::table& root,
                               std::string_view key) {
  const toml::node* node = root.get(key);
  if (node == nullptr) return nullptr;
  const toml::array* arr = node->as_array();
  if (arr == nullptr || !arr->is_array_of_tables()) {
    fail(file, node->source(), std::string(key), "expected [[" + std::string(key) + "]] tables");
  }
  return arr;
}

}  // namespace

ObjectModel parse_object_model(std::string_view source_text, const std::filesystem::path& file) {
  const toml::table root = parse_toml(source_text, file.string());
  reject_unknown(file, root, "", {"name", "part", "link"});
  ObjectModel model;
  model.name = text(file, required(file, root, "name", "name"), "name");
  const toml::array* parts = table_array(file, root, "part");
  if (parts == nullptr || parts->empty())
    fail(file, root.source(), "part", "at least one [[part]] is required");
  if (parts->size() > kMaxParts) fail(file, parts->source(), "part", "at most 16 parts");
  for (std::size_t i = 0; i < parts->size(); ++i) {
    ModelPart p = parse_part(file, *parts->get(i)->as_table(), i);
    for (const ModelPart& q : model.parts) {
      if (q.name == p.name)
        fail(file, parts->get(i)->source(), "part[" + std::to_string(i) + "].name",
             "duplicate part name '" + p.name + "'");
    }
    model.parts.push_back(std::move(p));
  }
  if (const toml::array* links = table_array(file, root, "link")) {
    for (std::size_t i = 0; i < links->size(); ++i) {
      model.links.push_back(parse_link(file, *links->get(i)->as_table(), i, model.parts));
    }
  }
  return model;
}

ObjectModel read_object_model(const std::filesystem::path& path) {
  return parse_object_model(read_toml_file(path, kMaxFileBytes), path);
}

std::string format_object_model(const ObjectModel& model) {
  std::ostringstream out;
  out.precision(17);
  out << "name = \"" << model.name << "\"\n";
  for (const ModelPart& p : model.parts) {
    const Superquadric& s = p.shape;
    out << "\n[[part]]\nname = \"" << p.name << "\"\nsize = [" << s.a1 << ", " << s.a2 << ", "
        << s.a3 << "]\nshape = [" << s.eps1 << ", " << s.eps2 << "]\ntaper = [" << s.kx << ", "
        << s.ky << "]\n";
  }
  for (const PartLink& l : model.links) {
    out << "\n[[link]]\nparts = [\"" << model.parts.at(l.first).name << "\", \""
        << model.parts.at(l.second).name
        << "\"]\nangle_deg = " << l.angle_rad * 180.0 / std::numbers::pi
        << "\ndistance = " << l.distance_mm << "\n";
  }
  return out.str();
}

namespace {

// A name format_object_model can put between double quotes as it stands.
bool plain_name(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\' || u < 0x20 || u == 0x7f) return false;
  }
  return true;
}

void check_writable(const std::filesystem::path& path, const ObjectModel& model) {
  if (!plain_name(model.name))
    throw IoError(path, "model name '" + model.name + "' cannot be written");
  if (model.parts.empty()) throw IoError(path, "a model needs at least one part");
  if (model.parts.size() > kMaxParts) throw IoError(path, "at most 16 parts");
  for (std::size_t i = 0; i < model.parts.size(); ++i) {
    const ModelPart& p = model.parts[i];
    if (!plain_name(p.name)) throw IoError(path, "part name '" + p.name + "' cannot be written");
    if (!p.shape.valid()) throw IoError(path, "part '" + p.name + "' is not a valid superquadric");
    for (std::size_t j = 0; j < i; ++j) {
      if (model.parts[j].name == p.name)
        throw IoError(path, "duplicate part name '" + p.name + "'");
    }
  }
  for (const PartLink& l : model.links) {
    if (l.first >= model.parts.size() || l.second >= model.parts.size() || l.first == l.second ||
        !(l.angle_rad >= 0.0 && l.angle_rad <= std::numbers::pi) || !(l.distance_mm >= 0.0)) {
      throw IoError(path, "invalid link");
    }
  }
}

}  // namespace

void write_object_model(const std::filesystem::path& path, const ObjectModel& model,
                        std::string_view comment) {
  check_writable(path, model);
  std::string text;
  std::string_view rest = comment;
  while (!rest.empty()) {
    const std::size_t eol = rest.find('\n');
    text += "# ";
    text += rest.substr(0, eol);
    text += "\n";
    rest = eol == std::string_view::npos ? std::string_view{} : rest.substr(eol + 1);
  }
  text += format_object_model(model);
  if (path == "-") {
    std::cout << text << std::flush;
    if (!std::cout) throw IoError(path, "cannot write to standard output");
    return;
  }
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(path, "cannot open " + tmp.string() + " for writing");
    out << text;
    out.flush();
    if (!out) throw IoError(path, "cannot write " + tmp.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw IoError(path, "cannot replace the file: " + ec.message());
  }
}

}  // namespace rangefit::io
