#include "io/object_model_file.hpp"

#include <toml++/toml.h>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <system_error>

#include "io/io_error.hpp"
#include "io/toml_fields.hpp"
#include "io/toml_file.hpp"

namespace rangefit::io {
namespace {

constexpr std::size_t kMaxFileBytes = 1 << 20;  // model files are tiny; refuse anything huge
constexpr std::size_t kMaxParts = 16;

// A non-empty string that must be present.
std::string name_of(TomlFields& f, std::string_view key) {
  f.require(key);
  std::string v;
  f.read(key, v);
  if (v.empty()) f.fail(key, "must be a non-empty string");
  return v;
}

ModelPart parse_part(TomlFields f) {
  f.only({"name", "size", "shape", "taper"});
  ModelPart part;
  part.name = name_of(f, "name");
  std::array<double, 3> size{};
  f.require("size", "(three half-sizes, mm)");
  f.read("size", size, 1e-9, 1e9);
  std::array<double, 2> shape{};
  f.require("shape", "(eps1, eps2)");
  f.read("shape", shape, 0.1, 2.0);
  std::array<double, 2> taper{0.0, 0.0};
  f.read("taper", taper, -1.0, 1.0);
  f.reject_unknown();
  part.shape = Superquadric{size[0], size[1], size[2], shape[0], shape[1], taper[0], taper[1]};
  return part;
}

PartLink parse_link(TomlFields f, const std::vector<ModelPart>& parts) {
  f.only({"parts", "angle_deg", "distance", "bearing_deg"});
  f.require("parts", "(two part names)");
  const toml::array* names = f.find("parts")->as_array();
  if (names == nullptr || names->size() != 2 || !(*names)[0].is_string() ||
      !(*names)[1].is_string()) {
    f.fail("parts", "must be two part names");
  }
  std::size_t idx[2] = {0, 0};
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string name = (*names)[k].as_string()->get();
    std::size_t j = 0;
    while (j < parts.size() && parts[j].name != name) ++j;
    if (j == parts.size()) f.fail("parts", "no part named '" + name + "'");
    idx[k] = j;
  }
  if (idx[0] == idx[1]) f.fail("parts", "a part cannot link to itself");
  double angle = 0.0, distance = 0.0;
  f.require("angle_deg");
  f.read("angle_deg", angle, 0.0, 180.0);
  f.require("distance", "(mm)");
  f.read("distance", distance, 0.0, 1e9);
  PartLink link{idx[0], idx[1], angle * std::numbers::pi / 180.0, distance, std::nullopt};
  if (f.has("bearing_deg")) {
    std::array<double, 2> bearing{};
    f.read("bearing_deg", bearing, 0.0, 90.0);
    link.bearing_rad = {bearing[0] * std::numbers::pi / 180.0,
                        bearing[1] * std::numbers::pi / 180.0};
  }
  f.reject_unknown();
  return link;
}

}  // namespace

ObjectModel parse_object_model(std::string_view source_text, const std::filesystem::path& file) {
  const toml::table root = parse_toml(source_text, file.string());
  TomlFields f(&root, file.string());
  f.only({"name", "part", "link"});
  ObjectModel model;
  model.name = name_of(f, "name");
  const toml::array* parts = f.table_array("part");
  if (parts == nullptr || parts->empty()) f.fail("part", "at least one [[part]] is required");
  if (parts->size() > kMaxParts) f.fail("part", "at most 16 parts");
  for (std::size_t i = 0; i < parts->size(); ++i) {
    TomlFields pf = f.element("part", *parts, i);
    ModelPart p = parse_part(pf);
    for (const ModelPart& q : model.parts) {
      if (q.name == p.name) pf.fail("name", "duplicate part name '" + p.name + "'");
    }
    model.parts.push_back(std::move(p));
  }
  if (const toml::array* links = f.table_array("link")) {
    for (std::size_t i = 0; i < links->size(); ++i) {
      model.links.push_back(parse_link(f.element("link", *links, i), model.parts));
    }
  }
  f.reject_unknown();
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
    if (l.bearing_rad) {
      out << "bearing_deg = [" << (*l.bearing_rad)[0] * 180.0 / std::numbers::pi << ", "
          << (*l.bearing_rad)[1] * 180.0 / std::numbers::pi << "]\n";
    }
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
        !(l.angle_rad >= 0.0 && l.angle_rad <= std::numbers::pi) || !(l.distance_mm >= 0.0) ||
        !l.bearings_valid()) {
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
