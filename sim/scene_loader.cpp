#include "sim/scene_loader.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "detect/common/angles.hpp"
#include "hal/rpy.hpp"
#include "io/stl.hpp"
#include "io/toml_fields.hpp"
#include "io/toml_file.hpp"
#include "sim/bore_plate_mesh.hpp"

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;

// Limits on what a scene may ask for: generation time and memory grow with them (segments =
// 800000 took 33 s and 0.9 GB). Each is far above what the shipped scenes use.
constexpr std::int64_t kMaxSegments = 4096;  // points per bore ring (shipped: 64, 256)
constexpr std::int64_t kMaxNotches = 360;
constexpr std::size_t kMaxObjects = 1000;
constexpr std::size_t kMaxPlateBores = 100;
constexpr std::size_t kMaxTruthBores = 1000;

// The table being read, through the one field reader (io::TomlFields: "<file>:<line>:
// <path>.<field>: <problem>"), with the scene's way of giving defaults: each getter returns the
// value, or the fallback when the field is absent, or fails when there is none.
struct Ctx {
  mutable io::TomlFields f;

  [[noreturn]] void fail(std::string_view field, const std::string& what) const {
    f.fail(field, what);
  }
  bool has(std::string_view field) const { return f.has(field); }
  // Keys this version reads; any other is a typo that must not fall back to a default.
  void only(std::initializer_list<std::string_view> known) const { f.only(known); }
  Ctx element(std::string_view key, const toml::array& array, std::size_t i) const {
    if (!array[i].is_table()) fail(key, "must be an array of tables");
    return Ctx{f.element(key, array, i)};
  }

  // A whole number in [lo, hi], checked before any conversion (1e30 or 1e12 as an int is UB).
  int integer(std::string_view field, std::int64_t fallback, std::int64_t lo,
              std::int64_t hi) const {
    const double v = number(field, static_cast<double>(fallback));
    if (v != std::floor(v) || v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
      fail(field,
           "must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    return static_cast<int>(v);
  }

  template <class Array>
  void at_most(std::string_view field, const Array& arr, std::size_t limit) const {
    if (arr.size() > limit) fail(field, "has more than " + std::to_string(limit) + " entries");
  }

  double number(std::string_view field, std::optional<double> fallback = std::nullopt) const {
    if (!has(field) && !fallback) fail(field, "is missing");
    double v = fallback.value_or(0.0);
    f.read(field, v, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
    return v;
  }

  double positive(std::string_view field, std::optional<double> fallback = std::nullopt) const {
    const double v = number(field, fallback);
    if (!(v > 0.0)) fail(field, "must be positive");
    return v;
  }

  template <int N>
  Eigen::Matrix<double, N, 1> vec(std::string_view field,
                                  std::optional<Eigen::Matrix<double, N, 1>> fallback = {}) const {
    if (!has(field) && !fallback) fail(field, "is missing");
    std::array<double, N> v{};
    if (fallback) std::copy(fallback->data(), fallback->data() + N, v.begin());
    f.read(field, v, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
    return Eigen::Map<const Eigen::Matrix<double, N, 1>>(v.data());
  }

  std::string text(std::string_view field, std::optional<std::string> fallback = {}) const {
    if (!has(field) && !fallback) fail(field, "is missing");
    std::string v = fallback.value_or("");
    f.read(field, v);
    return v;
  }
};

Eigen::Isometry3d read_pose(const Ctx& c) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = c.vec<3>("position", Vector3d::Zero());
  if (c.has("rpy_deg") && c.has("z_axis")) c.fail("z_axis", "cannot be combined with rpy_deg");
  if (c.has("z_axis")) {
    const Vector3d z = c.vec<3>("z_axis");
    if (z.norm() < 1e-9) c.fail("z_axis", "must not be the zero vector");
    T.linear() =
        Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), z.normalized()).toRotationMatrix();
  } else {
    const Vector3d rpy = kDeg * c.vec<3>("rpy_deg", Vector3d::Zero());
    T.linear() = hal::rpy_matrix(rpy.x(), rpy.y(), rpy.z());
  }
  return T;
}

BoreSpec read_bore(const Ctx& c) {
  c.only({"name", "kind", "diameter", "slant_deg", "edge", "notches", "notch_depth",
          "notch_width_deg"});
  BoreSpec b;
  b.name = c.text("name");
  if (!parse_bore_kind(c.text("kind", "straight"), b.kind)) {
    c.fail("kind", "must be straight, slanted, chamfered, rounded or notched");
  }
  b.diameter_mm = c.positive("diameter");
  b.slant_rad = kDeg * c.number("slant_deg", b.kind == BoreKind::kSlanted ? 45.0 : 0.0);
  b.edge_mm = c.positive("edge", 1.0);
  b.notches = c.integer("notches", 6, 1, kMaxNotches);
  b.notch_depth_mm = c.positive("notch_depth", 2.0);
  b.notch_width_rad = kDeg * c.positive("notch_width_deg", 12.0);
  return b;
}

void read_object(const Ctx& c, const std::string& base_dir, Scene& scene) {
  SceneObject obj;
  obj.name = c.text("name");
  const std::string type = c.text("type");
  const Ctx& named = c;
  obj.T_world_object = read_pose(named);
  const auto only = [&](std::initializer_list<std::string_view> extra) {
    std::vector<std::string_view> known{"name", "type", "position", "rpy_deg", "z_axis"};
    known.insert(known.end(), extra.begin(), extra.end());
    for (const auto& [key, node] : *c.f.table()) {
      if (std::find(known.begin(), known.end(), key.str()) == known.end())
        named.fail(key.str(), "unknown field for type '" + type + "'");
    }
  };
  if (type == "plane") {
    only({"size"});
    const Eigen::Vector2d s = named.vec<2>("size", Eigen::Vector2d(1000.0, 1000.0));
    if (!(s.minCoeff() > 0.0)) named.fail("size", "must be positive");
    obj.shape = PlaneShape{s.x(), s.y()};
  } else if (type == "box") {
    only({"size"});
    const Vector3d s = named.vec<3>("size");
    if (!(s.minCoeff() > 0.0)) named.fail("size", "must be positive");
    obj.shape = BoxShape{s};
  } else if (type == "cylinder") {
    only({"radius", "height"});
    obj.shape = CylinderShape{named.positive("radius"), named.positive("height")};
  } else if (type == "sphere") {
    only({"radius"});
    obj.shape = SphereShape{named.positive("radius")};
  } else if (type == "superquadric") {
    only({"a", "eps", "taper"});
    const Vector3d a = named.vec<3>("a");
    const Eigen::Vector2d e = named.vec<2>("eps", Eigen::Vector2d(1.0, 1.0));
    const Eigen::Vector2d k = named.vec<2>("taper", Eigen::Vector2d(0.0, 0.0));
    if (!(a.minCoeff() > 0.0)) named.fail("a", "must be positive");
    if (!(e.minCoeff() >= 0.1 && e.maxCoeff() <= 2.0)) named.fail("eps", "must lie in [0.1, 2]");
    if (!(k.cwiseAbs().maxCoeff() <= 1.0)) named.fail("taper", "must lie in [-1, 1]");
    obj.shape = SuperquadricShape{Superquadric{a.x(), a.y(), a.z(), e.x(), e.y(), k.x(), k.y()}};
  } else if (type == "mesh") {
    only({"file"});
    const std::string file = named.text("file");
    const std::filesystem::path path = std::filesystem::path(base_dir) / file;
    try {
      obj.shape = MeshShape{io::read_stl(path), file};
    } catch (const std::exception& e) {
      named.fail("file", std::string("cannot be loaded: ") + e.what());
    }
  } else if (type == "bore_plate") {
    only({"cell", "thickness", "segments", "bore"});
    BorePlateSpec spec;
    spec.cell_mm = named.positive("cell", spec.cell_mm);
    spec.thickness_mm = named.positive("thickness", spec.thickness_mm);
    spec.segments = named.integer("segments", spec.segments, 8, kMaxSegments);
    const toml::array* bores = c.f.table()->get_as<toml::array>("bore");
    if (!bores) named.fail("bore", "is missing: a bore_plate needs [[object.bore]] tables");
    named.at_most("bore", *bores, kMaxPlateBores);
    for (std::size_t i = 0; i < bores->size(); ++i) {
      spec.bores.push_back(read_bore(c.element("bore", *bores, i)));
    }
    BorePlate plate = make_bore_plate(spec);
    if (!plate.error.empty()) named.fail("bore", "is invalid: " + plate.error);
    for (BoreTruth b : plate.bores) {
      b.opening_mm = obj.T_world_object * b.opening_mm;
      b.axis = obj.T_world_object.linear() * b.axis;
      scene.bores.push_back(b);
    }
    obj.shape = MeshShape{std::move(plate.mesh), "bore_plate"};
  } else {
    named.fail("type", "must be plane, box, cylinder, sphere, superquadric, mesh or bore_plate");
  }
  scene.objects.push_back(std::move(obj));
}

Scene read_scene(const Ctx& top, const std::string& base_dir) {
  Scene scene;
  scene.source = top.f.source();
  const toml::table& root = *top.f.table();
  top.only({"object", "bore", "sensors"});
  const toml::array* objects = root.get_as<toml::array>("object");
  if (!objects) top.fail("object", "is missing: a scene needs at least one [[object]]");
  top.at_most("object", *objects, kMaxObjects);
  for (std::size_t i = 0; i < objects->size(); ++i) {
    read_object(top.element("object", *objects, i), base_dir, scene);
  }
  // Ground truth of bores in mesh objects (a bore_plate object gives its own).
  if (const toml::array* bores = root.get_as<toml::array>("bore")) {
    top.at_most("bore", *bores, kMaxTruthBores);
    for (std::size_t i = 0; i < bores->size(); ++i) {
      const Ctx c = top.element("bore", *bores, i);
      c.only({"name", "kind", "diameter", "opening", "axis"});
      BoreTruth b;
      b.name = c.text("name");
      b.kind = c.text("kind", "straight");
      BoreKind kind;
      if (!parse_bore_kind(b.kind, kind)) {
        c.fail("kind", "must be straight, slanted, chamfered, rounded or notched");
      }
      b.diameter_mm = c.positive("diameter");
      b.opening_mm = c.vec<3>("opening");
      const Vector3d axis = c.vec<3>("axis");
      if (axis.norm() < 1e-9) c.fail("axis", "must not be the zero vector");
      b.axis = axis.normalized();
      scene.bores.push_back(b);
    }
  }
  if (const toml::table* sensors = top.f.sub_table("sensors")) {
    const Ctx sensor_table{top.f.sub("sensors")};
    sensor_table.only({"css", "stripe", "pantilt"});
    const std::pair<const char*, Eigen::Isometry3d*> mounts[] = {
        {"css", &scene.mounts.T_scene_css},
        {"stripe", &scene.mounts.T_scene_stripe},
        {"pantilt", &scene.mounts.T_scene_pantilt}};
    for (const auto& [key, pose] : mounts) {
      if (sensors->get_as<toml::table>(key) != nullptr) {
        const Ctx mount{sensor_table.f.sub(key)};
        mount.only({"position", "rpy_deg", "z_axis"});
        *pose = read_pose(mount);
      }
    }
  }
  return scene;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const std::string& base_dir) {
  try {
    const toml::table root = io::parse_toml(text, name);
    return read_scene(Ctx{io::TomlFields(&root, name)}, base_dir);
  } catch (const io::TomlError& e) {
    throw SceneError(e.what());
  }
}

Scene load_scene(const std::string& path) {
  std::string text;
  try {
    text = io::read_toml_file(path);
  } catch (const io::TomlError& e) {
    throw SceneError(e.what());
  }
  return parse_scene(text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace rangefit::sim
